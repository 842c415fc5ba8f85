!> Exact (order-independent) summation of double-precision numbers.
!>
!> A sum of doubles rounded at every step depends on the order of its terms,
!> so per-rank partial sums followed by MPI_SUM change with the partition.
!> Here every term is added exactly into a wide fixed-point integer (a
!> "long accumulator" in the manner of Kulisch): 66 limbs of 32 bits span
!> every double from 2^-1074 to 2^1024. Integer addition is associative, so
!> the limbs of several ranks are combined with an integer MPI_SUM and the
!> result is the same for any partition and any order; it is then rounded
!> once to the nearest double (ties to even). Pure kernels, no state.
module udar_exact_sum
  use udar_kinds, only: rk, i8
  implicit none
  private
  public :: exact_limbs, exact_clear, exact_add, exact_normalize, exact_value, exact_sum_of

  integer, parameter :: exact_limbs = 66       !< 32-bit digits per accumulator
  integer(i8), parameter :: mask32 = 4294967295_i8
  integer(i8), parameter :: mask52 = 4503599627370495_i8
  !> limbs are normalized after this many additions: each adds less than
  !> 2^32 in magnitude to a limb, so an int64 limb cannot overflow
  integer, parameter :: adds_between_carries = 2**30

contains

  pure subroutine exact_clear(acc)
    integer(i8), intent(out) :: acc(0:exact_limbs)   !< limbs 0..65, slot 66 counts additions
    acc = 0_i8
  end subroutine

  !> acc += x, exactly. Non-finite terms are not representable and are the
  !> caller's business (the run stops on a non-finite energy anyway): they
  !> are mapped to the largest finite value with their sign.
  pure subroutine exact_add(acc, x)
    integer(i8), intent(inout) :: acc(0:exact_limbs)
    real(rk), intent(in) :: x
    integer(i8) :: bits, m, p0, p1, p2
    integer :: e, s, k, r
    if (x == 0.0_rk) return
    bits = transfer(x, bits)
    e = int(iand(ishft(bits, -52), 2047_i8))
    m = iand(bits, mask52)
    if (e == 2047) then              ! inf or NaN
      e = 2046
      m = mask52
    end if
    if (e > 0) m = ior(m, ishft(1_i8, 52))
    s = max(e, 1) - 1                ! x = m * 2^(s - 1074)
    k = s/32
    r = s - 32*k
    p0 = iand(ishft(m, r), mask32)
    p1 = iand(ishft(m, r - 32), mask32)
    p2 = ishft(m, r - 64)
    if (bits < 0) then
      p0 = -p0; p1 = -p1; p2 = -p2
    end if
    acc(k) = acc(k) + p0
    acc(k+1) = acc(k+1) + p1
    acc(k+2) = acc(k+2) + p2
    acc(exact_limbs) = acc(exact_limbs) + 1
    if (acc(exact_limbs) >= adds_between_carries) call exact_normalize(acc)
  end subroutine

  !> Carry propagation: limbs 0..64 in [0, 2^32), the sign in the top limb.
  !> The value is unchanged; normalized accumulators can be summed limb by
  !> limb (integer MPI_SUM of up to 2^30 of them) and normalized again.
  pure subroutine exact_normalize(acc)
    integer(i8), intent(inout) :: acc(0:exact_limbs)
    integer(i8) :: carry
    integer :: k
    do k = 0, exact_limbs - 2
      carry = shifta(acc(k), 32)     ! floor(acc(k) / 2^32)
      acc(k) = acc(k) - ishft(carry, 32)
      acc(k+1) = acc(k+1) + carry
    end do
    acc(exact_limbs) = 0_i8
  end subroutine

  !> The accumulated sum rounded to the nearest double (ties to even). The
  !> rounding depends only on the exact value, never on how it was summed.
  pure real(rk) function exact_value(acc_in) result(v)
    integer(i8), intent(in) :: acc_in(0:exact_limbs)
    integer(i8) :: a(0:exact_limbs), carry, m, rest
    integer :: k, top, nbits, shift, b
    logical :: negative, sticky
    a = acc_in
    call exact_normalize(a)
    negative = a(exact_limbs-1) < 0
    if (negative) then               ! magnitude: two's complement over the limbs
      carry = 1_i8
      do k = 0, exact_limbs - 1
        a(k) = iand(not(a(k)), mask32) + carry
        carry = ishft(a(k), -32)
        a(k) = iand(a(k), mask32)
      end do
    end if
    top = -1
    do k = exact_limbs - 1, 0, -1
      if (a(k) /= 0) then
        top = k
        exit
      end if
    end do
    if (top < 0) then
      v = 0.0_rk
      return
    end if
    ! position of the leading bit, counted in units of 2^-1074 from bit 0
    nbits = 32*top + (bit_size(a(top)) - leadz(a(top)))
    ! keep 53 significant bits (fewer in the subnormal range, where shift = 0)
    shift = max(nbits - 53, 0)
    m = extract(a, shift, min(nbits, 53))
    rest = 0_i8
    sticky = .false.
    if (shift > 0) then
      rest = extract(a, shift - 1, 1)               ! the first dropped bit
      do b = 0, shift - 2                          ! any bit below it
        if (extract(a, b, 1) /= 0) then
          sticky = .true.
          exit
        end if
      end do
      if (rest /= 0 .and. (sticky .or. iand(m, 1_i8) /= 0)) m = m + 1
    end if
    ! m * 2^(shift - 1074): exact, m has at most 53 bits
    v = scale(real(m, rk), shift - 1074)
    if (negative) v = -v
  end function

  !> The sum of values rounded once to the nearest double (ties to even):
  !> what Python's math.fsum gives, and for two values their IEEE sum.
  pure real(rk) function exact_sum_of(values) result(v)
    real(rk), intent(in) :: values(:)
    integer(i8) :: acc(0:exact_limbs)
    integer :: i
    call exact_clear(acc)
    do i = 1, size(values)
      call exact_add(acc, values(i))
    end do
    v = exact_value(acc)
  end function

  !> Bits [lo, lo+n) of the limb array as an integer (n <= 62).
  pure integer(i8) function extract(a, lo, n) result(r)
    integer(i8), intent(in) :: a(0:exact_limbs)
    integer, intent(in) :: lo, n
    integer :: b, k, i
    r = 0_i8
    do i = n - 1, 0, -1
      b = lo + i
      k = b/32
      r = ior(ishft(r, 1), iand(ishft(a(k), -(b - 32*k)), 1_i8))
    end do
  end function
end module udar_exact_sum
