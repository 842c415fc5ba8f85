!> Unit test of udar_exact_sum: exactness, order and split independence (what
!> makes the history the same on any number of ranks) and correct rounding.
program test_exact_sum
  use, intrinsic :: iso_fortran_env, only: real128
  use udar_kinds, only: rk, i8
  use udar_strings, only: r2s
  use udar_exact_sum, only: exact_limbs, exact_clear, exact_add, exact_normalize, exact_value, exact_sum_of
  use unit_checks, only: check, check_summary
  implicit none
  integer, parameter :: n = 20000
  real(rk) :: x(n), u(n), naive_fwd, naive_rev
  real(real128) :: ref
  integer(i8) :: acc(0:exact_limbs), part(0:exact_limbs, 3), rev(0:exact_limbs)
  integer :: i, k

  ! cancellation a naive sum loses
  call exact_clear(acc)
  call exact_add(acc, 1.0e16_rk); call exact_add(acc, 1.0_rk); call exact_add(acc, -1.0e16_rk)
  call check('cancellation', exact_value(acc) == 1.0_rk, '1e16 + 1 - 1e16 = '//r2s(exact_value(acc)))

  ! mixed signs and magnitudes 2^-20..2^20: a quad-precision sum is exact here
  call random_seed(put=[(12345 + i, i = 1, 64)])
  call random_number(u)
  call random_number(x)
  x = (x - 0.45_rk)*2.0_rk**(nint(40*u) - 20)
  ref = 0
  do i = 1, n
    ref = ref + real(x(i), real128)
  end do
  call exact_clear(acc)
  naive_fwd = 0
  do i = 1, n
    call exact_add(acc, x(i))
    naive_fwd = naive_fwd + x(i)
  end do
  call exact_clear(rev)
  naive_rev = 0
  do i = n, 1, -1
    call exact_add(rev, x(i))
    naive_rev = naive_rev + x(i)
  end do
  call check('correctly_rounded', exact_value(acc) == real(ref, rk), &
             'exact '//r2s(exact_value(acc))//' vs quad '//r2s(real(ref, rk)))
  call check('order_independent', &
             exact_value(acc) == exact_value(rev), 'forward and reverse sums bitwise equal')
  call check('naive_sum_is_order_dependent', naive_fwd /= naive_rev .or. naive_fwd == real(ref, rk), &
             'naive forward - reverse = '//r2s(naive_fwd - naive_rev)//' (why the exact sum exists)')

  ! three "ranks" with interleaved shares, combined by an integer sum
  do k = 1, 3
    call exact_clear(part(:,k))
    do i = k, n, 3
      call exact_add(part(:,k), x(i))
    end do
    call exact_normalize(part(:,k))
  end do
  acc = part(:,1) + part(:,2) + part(:,3)
  call exact_normalize(acc)
  call check('split_independent', exact_value(acc) == real(ref, rk), 'three partial accumulators summed as integers')

  ! negative totals, the extremes of the range, ties to even
  call exact_clear(acc)
  call exact_add(acc, -3.5_rk); call exact_add(acc, 1.25_rk)
  call check('negative_total', exact_value(acc) == -2.25_rk, r2s(exact_value(acc)))
  call exact_clear(acc)
  call exact_add(acc, 1.0e300_rk); call exact_add(acc, 1.0e300_rk); call exact_add(acc, -huge(1.0_rk)/4)
  call check('large_values', exact_value(acc) == 2.0e300_rk - huge(1.0_rk)/4, r2s(exact_value(acc)))
  call exact_clear(acc)
  call exact_add(acc, tiny(1.0_rk)); call exact_add(acc, -tiny(1.0_rk)/2**20)
  call check('subnormal', exact_value(acc) == tiny(1.0_rk) - tiny(1.0_rk)/2**20, r2s(exact_value(acc)))
  call exact_clear(acc)
  call exact_add(acc, 1.0_rk); call exact_add(acc, 2.0_rk**(-53))
  call check('tie_to_even_down', exact_value(acc) == 1.0_rk, '1 + 2^-53 rounds to 1')
  call exact_add(acc, 2.0_rk**(-105))
  call check('above_tie_rounds_up', exact_value(acc) == 1.0_rk + 2.0_rk**(-52), '1 + 2^-53 + 2^-105')
  call exact_clear(acc)
  call exact_add(acc, 1.0_rk + 2.0_rk**(-52)); call exact_add(acc, 2.0_rk**(-53))
  call check('tie_to_even_up', exact_value(acc) == 1.0_rk + 2.0_rk**(-51), '(1 + 2^-52) + 2^-53')
  call exact_clear(acc)
  call exact_add(acc, -0.1_rk); call exact_add(acc, 0.1_rk)
  call check('exact_zero', exact_value(acc) == 0.0_rk, r2s(exact_value(acc)))
  ! the history's totals of the part columns: math.fsum's value (here by hand:
  ! 1 + 2^-53 + 2^-53 = 1 + 2^-52 exactly, where adding left to right gives 1)
  call check('sum_of_three', exact_sum_of([1.0_rk, 2.0_rk**(-53), 2.0_rk**(-53)]) == 1.0_rk + 2.0_rk**(-52), &
             r2s(exact_sum_of([1.0_rk, 2.0_rk**(-53), 2.0_rk**(-53)])))
  call check('sum_of_two_is_ieee_sum', exact_sum_of([0.1_rk, 0.2_rk]) == 0.1_rk + 0.2_rk, '0.1 + 0.2')
  call check('sum_of_none', exact_sum_of([real(rk) ::]) == 0.0_rk, 'empty')
  call check_summary()
end program test_exact_sum
