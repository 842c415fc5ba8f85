!> Program identity, stored in every output file.
module udar_version
  implicit none
  private
  public :: program_version
  character(len=*), parameter :: program_version = '0.9.20'
end module udar_version
