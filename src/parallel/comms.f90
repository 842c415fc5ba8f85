!> The only user of MPI. Everything parallel goes through here, so the rest of
!> udar never sees a communicator and a single rank is simply the serial run.
module udar_comms
  use mpi_f08
  use udar_kinds, only: rk, i8
  implicit none
  private
  public :: comms_init, comms_finalize, comms_abort, comms_rank, comms_size, &
            comms_is_root, comms_barrier, comms_min, comms_max, comms_wtime

  integer :: my_rank = 0, n_ranks = 1
  logical :: initialised = .false.

contains

  subroutine comms_init()
    integer :: ierr
    call MPI_Init(ierr)
    call MPI_Comm_rank(MPI_COMM_WORLD, my_rank, ierr)
    call MPI_Comm_size(MPI_COMM_WORLD, n_ranks, ierr)
    initialised = .true.
  end subroutine

  subroutine comms_finalize()
    integer :: ierr
    if (initialised) call MPI_Finalize(ierr)
    initialised = .false.
  end subroutine

  !> Ends every rank with the given exit code (1 input, 2 physics, 3 I/O).
  subroutine comms_abort(code)
    integer, intent(in) :: code
    integer :: ierr
    if (initialised .and. n_ranks > 1) call MPI_Abort(MPI_COMM_WORLD, code, ierr)
    if (initialised) call MPI_Finalize(ierr)
    select case (code)
    case (1); error stop 1
    case (2); error stop 2
    case (3); error stop 3
    case default; error stop 4
    end select
  end subroutine

  integer function comms_rank()
    comms_rank = my_rank
  end function

  integer function comms_size()
    comms_size = n_ranks
  end function

  logical function comms_is_root()
    comms_is_root = (my_rank == 0)
  end function

  subroutine comms_barrier()
    integer :: ierr
    call MPI_Barrier(MPI_COMM_WORLD, ierr)
  end subroutine

  !> Exact global minimum (min is order independent, so bitwise reproducible).
  real(rk) function comms_min(a)
    real(rk), intent(in) :: a
    integer :: ierr
    call MPI_Allreduce(a, comms_min, 1, MPI_DOUBLE_PRECISION, MPI_MIN, MPI_COMM_WORLD, ierr)
  end function

  real(rk) function comms_max(a)
    real(rk), intent(in) :: a
    integer :: ierr
    call MPI_Allreduce(a, comms_max, 1, MPI_DOUBLE_PRECISION, MPI_MAX, MPI_COMM_WORLD, ierr)
  end function

  real(rk) function comms_wtime()
    comms_wtime = MPI_Wtime()
  end function
end module udar_comms
