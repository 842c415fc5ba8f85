!> Cache-friendly orderings: Morton (Z-order) keys of points and a stable
!> merge sort. Used once at set-up so that nodes and elements that are close
!> in space are close in memory; pure and deterministic (the same mesh gives
!> the same order on every rank). Also the small sorts and searches of
!> ascending integer lists the drivers share.
module udar_ordering
  use udar_kinds, only: rk, i8
  implicit none
  private
  public :: morton_keys, stable_sort_permutation, sorted_ints, sort_ints, find_sorted

  integer, parameter :: bits = 20    !< per axis: 60-bit keys

contains

  !> Morton key of each point of x(n,3), quantised on the bounding box.
  pure subroutine morton_keys(x, keys)
    real(rk), intent(in) :: x(:,:)
    integer(i8), intent(out) :: keys(:)
    real(rk) :: lo(3), span(3)
    integer(i8) :: q(3), key
    integer :: i, k, b
    if (size(x, 1) == 0) return
    lo = minval(x, dim=1)
    span = max(maxval(x, dim=1) - lo, tiny(1.0_rk))
    do i = 1, size(x, 1)
      do k = 1, 3
        q(k) = min(int((x(i,k) - lo(k))/span(k)*real(2**bits - 1, rk), i8), int(2**bits - 1, i8))
      end do
      key = 0_i8
      do b = bits - 1, 0, -1
        do k = 1, 3
          key = ior(ishft(key, 1), iand(ishft(q(k), -b), 1_i8))
        end do
      end do
      keys(i) = key
    end do
  end subroutine

  !> The values in ascending order (insertion sort: for short lists, a
  !> face's nodes, a graph row, a particle's neighbours).
  pure function sorted_ints(v) result(w)
    integer, intent(in) :: v(:)
    integer :: w(size(v))
    w = v
    call sort_ints(w)
  end function

  !> sorted_ints in place (no temporary: for the cycle's short lists).
  pure subroutine sort_ints(w)
    integer, intent(inout) :: w(:)
    integer :: i, j, t
    do i = 2, size(w)
      t = w(i)
      j = i - 1
      do while (j >= 1)
        if (w(j) <= t) exit
        w(j+1) = w(j)
        j = j - 1
      end do
      w(j+1) = t
    end do
  end subroutine

  !> Position of value g in the ascending array a (0: absent), by bisection.
  pure integer function find_sorted(a, g) result(k)
    integer, intent(in) :: a(:), g
    integer :: lo, hi, mid
    k = 0
    lo = 1
    hi = size(a)
    do while (lo <= hi)
      mid = (lo + hi)/2
      if (a(mid) == g) then
        k = mid
        return
      else if (a(mid) < g) then
        lo = mid + 1
      else
        hi = mid - 1
      end if
    end do
  end function

  !> perm such that keys(perm) is ascending; equal keys keep their order.
  pure subroutine stable_sort_permutation(keys, perm)
    integer(i8), intent(in) :: keys(:)
    integer, intent(out) :: perm(:)
    integer, allocatable :: work(:)
    integer :: n, width, lo, mid, hi, i, j, k
    n = size(keys)
    perm = [(i, i = 1, n)]
    allocate(work(n))
    width = 1
    do while (width < n)
      do lo = 1, n, 2*width
        mid = min(lo + width - 1, n)
        hi = min(lo + 2*width - 1, n)
        i = lo; j = mid + 1; k = lo
        do while (i <= mid .and. j <= hi)
          if (keys(perm(j)) < keys(perm(i))) then
            work(k) = perm(j); j = j + 1
          else
            work(k) = perm(i); i = i + 1
          end if
          k = k + 1
        end do
        work(k:k+mid-i) = perm(i:mid); k = k + mid - i + 1
        work(k:k+hi-j) = perm(j:hi)
        perm(lo:hi) = work(lo:hi)
      end do
      width = 2*width
    end do
  end subroutine
end module udar_ordering
