!> Small vector algebra shared by the kernels and the drivers.
module udar_vectors
  use udar_kinds, only: rk
  implicit none
  private
  public :: cross, gather_columns, tangent_basis

contains

  !> a x b.
  pure function cross(a, b) result(c)
    real(rk), intent(in) :: a(3), b(3)
    real(rk) :: c(3)
    c = [a(2)*b(3) - a(3)*b(2), a(3)*b(1) - a(1)*b(3), a(1)*b(2) - a(2)*b(1)]
  end function

  !> b(:,j) = a(:,idx(j)) for the columns of idx (the others left alone):
  !> a face's corners gathered by their node numbers without the heap
  !> temporary gfortran makes for a vector subscript of run-time length.
  pure subroutine gather_columns(b, a, idx)
    real(rk), intent(inout) :: b(:,:)
    real(rk), intent(in) :: a(:,:)
    integer, intent(in) :: idx(:)
    integer :: j
    do j = 1, size(idx)
      b(:,j) = a(:,idx(j))
    end do
  end subroutine

  !> Unit vectors t1, t2 with (t1, t2, n) right-handed and orthonormal, for
  !> a unit n: t1 across the axis n is furthest from.
  pure subroutine tangent_basis(n, t1, t2)
    real(rk), intent(in) :: n(3)
    real(rk), intent(out) :: t1(3), t2(3)
    real(rk) :: e(3)
    e = 0.0_rk
    e(minloc(abs(n), dim=1)) = 1.0_rk
    t1 = cross(e, n)
    t1 = t1/norm2(t1)
    t2 = cross(n, t1)
  end subroutine
end module udar_vectors
