!> Working precision and integer kinds: the only place kinds are chosen.
module udar_kinds
  use, intrinsic :: iso_fortran_env, only: real64, int32, int64
  implicit none
  private
  public :: rk, ik, i8, max_name_len, max_path_len, block_size, pi

  integer, parameter :: rk = real64     !< working precision (all physics)
  real(rk), parameter :: pi = 3.141592653589793238462643383279_rk
  integer, parameter :: ik = int32      !< local indices
  integer, parameter :: i8 = int64      !< global counters and file offsets
  integer, parameter :: max_name_len = 64
  integer, parameter :: max_path_len = 1024
  !> elements per vectorized block: also the size of the kernels' local
  !> block arrays (a compile-time size keeps them off the heap)
  integer, parameter :: block_size = 128
end module udar_kinds
