!> Small vector algebra shared by the kernels and the drivers.
module udar_vectors
  use udar_kinds, only: rk
  implicit none
  private
  public :: cross, gather_columns

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
end module udar_vectors
