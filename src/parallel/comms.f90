!> The only user of MPI. Everything parallel goes through here, so the rest of
!> udar never sees a communicator and a single rank is simply the serial run.
module udar_comms
  use mpi_f08
  use, intrinsic :: iso_c_binding, only: c_int
  use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
  use udar_kinds, only: rk, i8
  use udar_exact_sum, only: exact_limbs, exact_normalize
  implicit none
  private
  public :: comms_init, comms_finalize, comms_abort, comms_exit, comms_xor_i8, comms_rank, comms_size, &
            comms_is_root, comms_barrier, comms_min, comms_max, comms_wtime, &
            comms_min_int, comms_max_int, comms_max_i8, comms_sum_int, comms_sum_exact, comms_alltoall_counts, &
            comms_alltoallv_int, comms_alltoallv_real, comms_bcast_int, comms_halo_exchange, comms_halo_exchange_scalar, comms_allgather_count, comms_allgatherv_int, comms_allgatherv_real, comms_world_handle, comms_info_null_handle

  !> A halo: which local nodes go to and come from which neighbour rank.
  !> Built once (udar_halo); the exchange itself allocates nothing.
  type, public :: halo_t
    integer :: n_neighbors = 0
    integer, allocatable :: neighbor(:)                !< ranks
    integer, allocatable :: send_ptr(:), send_idx(:)   !< CSR over neighbours: local nodes sent
    integer, allocatable :: recv_ptr(:), recv_idx(:)   !< local nodes received (ghosts)
    real(rk), allocatable :: send_buf(:), recv_buf(:)  !< room for 6 reals per node
    type(MPI_Request), allocatable :: requests(:)
  end type

  integer, parameter, public :: halo_max_components = 6

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
    call exit_process(code)
  end subroutine

  !> Every rank calls this with the same code (a collective decision): all
  !> finalize and exit with it, no MPI_Abort needed.
  subroutine comms_exit(code)
    integer, intent(in) :: code
    integer :: ierr
    if (initialised) then
      call MPI_Barrier(MPI_COMM_WORLD, ierr)
      if (code == 0) call MPI_Finalize(ierr)
    end if
    initialised = .false.
    call exit_process(code, quick=code /= 0)
  end subroutine

  !> Exit with code, Fortran units flushed. quick: without the library
  !> clean-ups (atexit handlers): after an I/O failure HDF5 would try again
  !> to flush a file on a full disk and crash (the ranks have met at a
  !> barrier and MPI is not finalized either, for the same reason).
  subroutine exit_process(code, quick)
    integer, intent(in) :: code
    logical, intent(in), optional :: quick
    interface
      subroutine c_exit(status) bind(c, name='exit')
        import :: c_int
        integer(c_int), value :: status
      end subroutine
      subroutine c_exit_now(status) bind(c, name='_exit')
        import :: c_int
        integer(c_int), value :: status
      end subroutine
    end interface
    flush(output_unit)
    flush(error_unit)
    if (present(quick)) then
      if (quick) call c_exit_now(int(code, c_int))
    end if
    call c_exit(int(code, c_int))
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

  integer function comms_min_int(a)
    integer, intent(in) :: a
    integer :: ierr
    call MPI_Allreduce(a, comms_min_int, 1, MPI_INTEGER, MPI_MIN, MPI_COMM_WORLD, ierr)
  end function

  integer function comms_max_int(a)
    integer, intent(in) :: a
    integer :: ierr
    call MPI_Allreduce(a, comms_max_int, 1, MPI_INTEGER, MPI_MAX, MPI_COMM_WORLD, ierr)
  end function

  integer(i8) function comms_max_i8(a)
    integer(i8), intent(in) :: a
    integer :: ierr
    call MPI_Allreduce(a, comms_max_i8, 1, MPI_INTEGER8, MPI_MAX, MPI_COMM_WORLD, ierr)
  end function

  !> Integer sums are exact, so any reduction order gives the same result.
  !> Bitwise exclusive or over the ranks (order-free: checksums of rows
  !> held by different ranks).
  integer(i8) function comms_xor_i8(a)
    integer(i8), intent(in) :: a
    integer :: ierr
    call MPI_Allreduce(a, comms_xor_i8, 1, MPI_INTEGER8, MPI_BXOR, MPI_COMM_WORLD, ierr)
  end function

  integer(i8) function comms_sum_int(a)
    integer(i8), intent(in) :: a
    integer :: ierr
    call MPI_Allreduce(a, comms_sum_int, 1, MPI_INTEGER8, MPI_SUM, MPI_COMM_WORLD, ierr)
  end function

  !> Global sum of exact accumulators (udar_exact_sum), one per column: the
  !> limbs are normalized, summed as integers (exact, order independent)
  !> and normalized again. Every rank gets the result.
  subroutine comms_sum_exact(acc)
    integer(i8), intent(inout) :: acc(0:, :)
    integer :: ierr, j
    do j = 1, size(acc, 2)
      call exact_normalize(acc(:,j))
    end do
    if (n_ranks > 1) call MPI_Allreduce(MPI_IN_PLACE, acc, size(acc), MPI_INTEGER8, MPI_SUM, MPI_COMM_WORLD, ierr)
    do j = 1, size(acc, 2)
      call exact_normalize(acc(:,j))
    end do
    if (size(acc, 1) /= exact_limbs + 1) call comms_abort(4)
  end subroutine

  !> recv_counts(q) = what rank q puts in send_counts(me), for every q.
  subroutine comms_alltoall_counts(send_counts, recv_counts)
    integer, intent(in) :: send_counts(0:)
    integer, intent(out) :: recv_counts(0:)
    integer :: ierr
    call MPI_Alltoall(send_counts, 1, MPI_INTEGER, recv_counts, 1, MPI_INTEGER, MPI_COMM_WORLD, ierr)
  end subroutine

  !> Personalized exchange of integers; displacements are the prefix sums of the counts.
  subroutine comms_alltoallv_int(send, send_counts, recv, recv_counts)
    integer, intent(in) :: send(:), send_counts(0:), recv_counts(0:)
    integer, intent(out) :: recv(:)
    integer :: ierr
    call MPI_Alltoallv(send, send_counts, offsets(send_counts), MPI_INTEGER, recv, recv_counts, offsets(recv_counts), MPI_INTEGER, &
                       MPI_COMM_WORLD, ierr)
  end subroutine

  !> As comms_alltoallv_int, for reals.
  subroutine comms_alltoallv_real(send, send_counts, recv, recv_counts)
    real(rk), intent(in) :: send(:)
    integer, intent(in) :: send_counts(0:), recv_counts(0:)
    real(rk), intent(out) :: recv(:)
    integer :: ierr
    call MPI_Alltoallv(send, send_counts, offsets(send_counts), MPI_DOUBLE_PRECISION, recv, recv_counts, offsets(recv_counts), &
                       MPI_DOUBLE_PRECISION, MPI_COMM_WORLD, ierr)
  end subroutine

  !> Where each rank's part starts in a buffer of the ranks' parts in
  !> rank order (the prefix sums of counts).
  pure function offsets(counts) result(disp)
    integer, intent(in) :: counts(0:)
    integer :: disp(0:size(counts)-1), q
    disp(0) = 0
    do q = 1, size(counts) - 1
      disp(q) = disp(q-1) + counts(q-1)
    end do
  end function

  !> counts(q) = n of rank q, on every rank.
  subroutine comms_allgather_count(n, counts)
    integer, intent(in) :: n
    integer, intent(out) :: counts(0:)
    integer :: ierr
    call MPI_Allgather(n, 1, MPI_INTEGER, counts, 1, MPI_INTEGER, MPI_COMM_WORLD, ierr)
  end subroutine

  !> Every rank's send(1:counts(rank)) concatenated in rank order, on every rank.
  subroutine comms_allgatherv_int(send, counts, recv)
    integer, intent(in) :: send(:), counts(0:)
    integer, intent(out) :: recv(:)
    integer :: ierr
    call MPI_Allgatherv(send, counts(my_rank), MPI_INTEGER, recv, counts, offsets(counts), MPI_INTEGER, MPI_COMM_WORLD, ierr)
  end subroutine

  !> As comms_allgatherv_int, for reals (counts in reals).
  subroutine comms_allgatherv_real(send, counts, recv)
    real(rk), intent(in) :: send(:)
    integer, intent(in) :: counts(0:)
    real(rk), intent(out) :: recv(:)
    integer :: ierr
    call MPI_Allgatherv(send, counts(my_rank), MPI_DOUBLE_PRECISION, recv, counts, offsets(counts), MPI_DOUBLE_PRECISION, &
                        MPI_COMM_WORLD, ierr)
  end subroutine

  !> Rank 0's array to every rank.
  subroutine comms_bcast_int(a)
    integer, intent(inout) :: a(:)
    integer :: ierr
    if (n_ranks > 1) call MPI_Bcast(a, size(a), MPI_INTEGER, 0, MPI_COMM_WORLD, ierr)
  end subroutine

  !> Owners' values of a(nc,:) (nc <= 6 components per node) and, if given,
  !> b(nc,:) into the ghost entries of every rank. Values are copied, never
  !> summed, so the result cannot depend on message order.
  subroutine comms_halo_exchange(h, a, b)
    type(halo_t), intent(inout) :: h
    real(rk), intent(inout) :: a(:,:)
    real(rk), intent(inout), optional :: b(:,:)
    integer :: nc, na, i, k, c, off, ierr
    if (h%n_neighbors == 0) return
    na = size(a, 1)
    nc = na
    if (present(b)) nc = na + size(b, 1)
    do i = 1, h%n_neighbors
      off = nc*(h%recv_ptr(i) - 1)
      call MPI_Irecv(h%recv_buf(off+1), nc*(h%recv_ptr(i+1) - h%recv_ptr(i)), MPI_DOUBLE_PRECISION, &
                     h%neighbor(i), 71, MPI_COMM_WORLD, h%requests(i), ierr)
    end do
    do k = 1, h%send_ptr(h%n_neighbors+1) - 1
      off = nc*(k - 1)
      do c = 1, na
        h%send_buf(off + c) = a(c, h%send_idx(k))
      end do
      if (present(b)) then
        do c = 1, nc - na
          h%send_buf(off + na + c) = b(c, h%send_idx(k))
        end do
      end if
    end do
    do i = 1, h%n_neighbors
      off = nc*(h%send_ptr(i) - 1)
      call MPI_Isend(h%send_buf(off+1), nc*(h%send_ptr(i+1) - h%send_ptr(i)), MPI_DOUBLE_PRECISION, &
                     h%neighbor(i), 71, MPI_COMM_WORLD, h%requests(h%n_neighbors + i), ierr)
    end do
    call MPI_Waitall(2*h%n_neighbors, h%requests, MPI_STATUSES_IGNORE, ierr)
    do k = 1, h%recv_ptr(h%n_neighbors+1) - 1
      off = nc*(k - 1)
      do c = 1, na
        a(c, h%recv_idx(k)) = h%recv_buf(off + c)
      end do
      if (present(b)) then
        do c = 1, nc - na
          b(c, h%recv_idx(k)) = h%recv_buf(off + na + c)
        end do
      end if
    end do
  end subroutine

  !> comms_halo_exchange for one value per node.
  subroutine comms_halo_exchange_scalar(h, s)
    type(halo_t), intent(inout) :: h
    real(rk), intent(inout), target :: s(:)
    real(rk), pointer :: s2(:,:)
    s2(1:1, 1:size(s)) => s
    call comms_halo_exchange(h, s2)
  end subroutine

  real(rk) function comms_wtime()
    comms_wtime = MPI_Wtime()
  end function

  !> MPI_COMM_WORLD as a default integer handle, for the HDF5 Fortran API
  !> (h5pset_fapl_mpio_f) that does not take mpi_f08 types.
  integer function comms_world_handle()
    comms_world_handle = MPI_COMM_WORLD%MPI_VAL
  end function

  !> MPI_INFO_NULL as a default integer handle (see comms_world_handle).
  integer function comms_info_null_handle()
    comms_info_null_handle = MPI_INFO_NULL%MPI_VAL
  end function
end module udar_comms
