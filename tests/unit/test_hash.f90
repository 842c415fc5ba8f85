!> Unit test of udar_hash: the published FNV-1a 64 test vectors, and that
!> the array hashes see every bit (what tells a foreign checkpoint).
program test_hash
  use udar_kinds, only: rk, i8
  use udar_hash, only: fnv_offset, hash_text, hash_ints, hash_reals, hash_hex
  use unit_checks, only: check, check_summary
  implicit none
  real(rk) :: x(3)
  integer(i8) :: h1, h2
  call check('fnv1a_empty', hash_hex(hash_text(fnv_offset, '')) == 'cbf29ce484222325', 'offset basis')
  call check('fnv1a_a', hash_hex(hash_text(fnv_offset, 'a')) == 'af63dc4c8601ec8c', hash_hex(hash_text(fnv_offset, 'a')))
  call check('fnv1a_foobar', hash_hex(hash_text(fnv_offset, 'foobar')) == '85944171f73967e8', &
             hash_hex(hash_text(fnv_offset, 'foobar')))
  x = [1.0_rk, 2.0_rk, 3.0_rk]
  h1 = hash_reals(fnv_offset, x)
  x(2) = nearest(x(2), 1.0_rk)
  h2 = hash_reals(fnv_offset, x)
  call check('one_ulp_changes_hash', h1 /= h2, hash_hex(h1)//' vs '//hash_hex(h2))
  call check('int_order_matters', hash_ints(fnv_offset, [1, 2]) /= hash_ints(fnv_offset, [2, 1]), 'connectivity order')
  call check_summary()
end program test_hash
