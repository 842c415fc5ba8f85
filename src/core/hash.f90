!> 64-bit FNV-1a hashes of text and of integer/real arrays (their bit
!> patterns), to recognise a checkpoint's deck and mesh. Not cryptographic:
!> it tells a different model from the right one, it does not resist forgery.
module udar_hash
  use udar_kinds, only: rk, i8
  implicit none
  private
  public :: fnv_offset, hash_text, hash_ints, hash_i8s, hash_reals, hash_hex

  integer(i8), parameter :: fnv_offset = -3750763034362895579_i8   ! 0xcbf29ce484222325

contains

  !> Continue hash h over the bytes of a string.
  pure integer(i8) function hash_text(h, s) result(r)
    integer(i8), intent(in) :: h
    character(len=*), intent(in) :: s
    integer :: i
    r = h
    do i = 1, len(s)
      r = mix(r, int(ichar(s(i:i)), i8))
    end do
  end function

  pure integer(i8) function hash_ints(h, a) result(r)
    integer(i8), intent(in) :: h
    integer, intent(in) :: a(:)
    r = hash_i8s(h, int(a, i8))
  end function

  pure integer(i8) function hash_i8s(h, a) result(r)
    integer(i8), intent(in) :: h
    integer(i8), intent(in) :: a(:)
    integer :: i
    r = h
    do i = 1, size(a)
      r = mix_word(r, a(i))
    end do
  end function

  pure integer(i8) function hash_reals(h, a) result(r)
    integer(i8), intent(in) :: h
    real(rk), intent(in) :: a(:)
    integer :: i
    r = h
    do i = 1, size(a)
      r = mix_word(r, transfer(a(i), 0_i8))
    end do
  end function

  !> 16 hexadecimal digits.
  pure function hash_hex(h) result(s)
    integer(i8), intent(in) :: h
    character(len=16) :: s
    character(len=16), parameter :: digits = '0123456789abcdef'
    integer :: k
    do k = 0, 15
      s(16-k:16-k) = digits(int(iand(ishft(h, -4*k), 15_i8)) + 1:int(iand(ishft(h, -4*k), 15_i8)) + 1)
    end do
  end function

  !> One byte into the hash: xor, then multiply by the FNV prime 2^40 + 435
  !> modulo 2^64, done on 32-bit halves so no signed product overflows.
  pure integer(i8) function mix(h, byte) result(r)
    integer(i8), intent(in) :: h, byte
    integer(i8), parameter :: mask32 = 4294967295_i8, mask24 = 16777215_i8
    integer(i8) :: x, hl, hh, lo, hi
    x = ieor(h, byte)
    hl = iand(x, mask32)
    hh = iand(ishft(x, -32), mask32)
    lo = hl*435_i8
    hi = iand(hh*435_i8 + ishft(lo, -32) + ishft(iand(hl, mask24), 8), mask32)
    r = ior(ishft(hi, 32), iand(lo, mask32))
  end function

  pure integer(i8) function mix_word(h, w) result(r)
    integer(i8), intent(in) :: h, w
    integer :: k
    r = h
    do k = 0, 7
      r = mix(r, iand(ishft(w, -8*k), 255_i8))
    end do
  end function
end module udar_hash
