!> File-system operations Fortran lacks: atomic rename and remove (C library).
module udar_files
  use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char
  implicit none
  private
  public :: rename_file, remove_if_present

  interface
    function c_rename(old, new) bind(c, name='rename') result(r)
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: old(*), new(*)
      integer(c_int) :: r
    end function
    function c_remove(path) bind(c, name='remove') result(r)
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int) :: r
    end function
  end interface

contains

  !> Atomic replacement of new by old (same file system); .false. on failure.
  logical function rename_file(old, new) result(ok)
    character(len=*), intent(in) :: old, new
    ok = c_rename(old//c_null_char, new//c_null_char) == 0
  end function

 !> Removes path if it exists; a missing file is not an error.
  subroutine remove_if_present(path)
    character(len=*), intent(in) :: path
    if (c_remove(path//c_null_char) /= 0) return
  end subroutine
end module udar_files
