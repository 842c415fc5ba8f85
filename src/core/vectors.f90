!> Small vector algebra shared by the kernels and the drivers.
module udar_vectors
  use udar_kinds, only: rk
  implicit none
  private
  public :: cross

contains

  !> a x b.
  pure function cross(a, b) result(c)
    real(rk), intent(in) :: a(3), b(3)
    real(rk) :: c(3)
    c = [a(2)*b(3) - a(3)*b(2), a(3)*b(1) - a(1)*b(3), a(1)*b(2) - a(2)*b(1)]
  end function
end module udar_vectors
