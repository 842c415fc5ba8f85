!> Collective field output on any number of ranks: every rank writes the
!> same small mesh (100 nodes, 60 tets, 2 steps with a node vector, a node
!> scalar and an element scalar) but owns only scattered rows of it, and the
!> file must not depend on the rank count.  Rank r owns node i when
!> mod(7*i+3, N) == r (many runs of rows per rank: more than the 16 that
!> the writer selects one by one before it merges selections); elements the
!> same way on 1 or 2 ranks, while on 3 or more ranks rank 0 owns no
!> element at all (owner 1 + mod(7*e+3, N-1)).  The file also goes through
!> a restart (fw_reopen keeping step 0, then step 1 written again).
!>
!> Usage: [mpirun -np N] test_field_output_mpi [<data_dir>] <output_dir>
!> Writes <output_dir>/npN.h5 (+ .xmf), reads it back on rank 0 and checks
!> every value.  tests/cli/field_output_ranks.sh runs it on 1, 2 and 3
!> ranks and compares the files with h5diff.
program test_field_output_mpi
  use, intrinsic :: iso_c_binding, only: c_ptr, c_loc, c_char, c_int, c_null_char
  use udar_kinds, only: rk, ik, i8
  use udar_field_output
  use udar_comms, only: comms_init, comms_finalize, comms_abort, comms_rank, comms_size, &
                        comms_is_root, comms_barrier
  use hdf5
  implicit none

  interface
    function c_mkdir(path, mode) bind(c, name='mkdir') result(r)
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int), value :: mode
      integer(c_int) :: r
    end function c_mkdir
  end interface

  integer, parameter :: nn = 100, ne = 60
  integer :: n_fail = 0
  integer :: me, np, i, k, nargs
  character(len=1024) :: outdir
  character(len=16) :: tag
  character(len=:), allocatable :: h5path, xmfpath, errmsg
  type(field_writer_t) :: w
  integer(ik) :: node_id(nn), elem_id(ne), part_id(ne), conn(ne, 4)
  real(rk) :: x0(nn, 3), xs(nn, 3, 0:1), vel(nn, 3, 0:1), mass(nn), p(ne, 0:1)
  real(rk), parameter :: times(0:1) = [0.0_rk, 1.5e-6_rk]
  integer(ik), allocatable :: ng(:), eg(:)
  logical :: ok
  integer(c_int) :: irc

  call comms_init()
  me = comms_rank()
  np = comms_size()
  nargs = command_argument_count()
  if (nargs < 1) then
    if (comms_is_root()) write(*, '(a)') 'usage: test_field_output_mpi [<data_dir>] <output_dir>'
    call comms_abort(1)
  end if
  call get_command_argument(nargs, outdir)
  if (comms_is_root()) then
    do i = 2, len_trim(outdir)
      if (outdir(i:i) == '/') irc = c_mkdir(outdir(1:i-1)//c_null_char, int(o'755', c_int))
    end do
    irc = c_mkdir(trim(outdir)//c_null_char, int(o'755', c_int))
  end if
  call comms_barrier()
  write(tag, '(a,i0)') 'np', np
  h5path = trim(outdir)//'/'//trim(tag)//'.h5'
  xmfpath = trim(outdir)//'/'//trim(tag)//'.xmf'

  ! ------------------------------------------------ the global mesh and data
  do i = 1, nn
    x0(i, :) = [real(i, rk), 0.1_rk*i*i, -0.5_rk*i]
    node_id(i) = 1000 + 3*i
    mass(i) = 0.25_rk*i + 1.0_rk/3.0_rk
    do k = 0, 1
      vel(i, :, k) = [real(i, rk), 10.0_rk*i, 100.0_rk*i]*(k + 1) + 1.0_rk/7.0_rk
      xs(i, :, k) = x0(i, :) + times(k)*vel(i, :, k)
    end do
  end do
  do i = 1, ne - 1
    conn(i, :) = [i, i + 1, i + 2, i + 3]
  end do
  conn(ne, :) = [1, 3, nn - 1, nn]
  do i = 1, ne
    elem_id(i) = 50 + 7*i
    part_id(i) = 1 + mod(i, 2)
    p(i, 0) = 1.0e5_rk*i
    p(i, 1) = -3.5_rk*i + 1.0_rk/9.0_rk
  end do

  ! ------------------------------------------------ this rank's rows
  ng = pack([(int(i, ik), i = 1, nn)], [(node_owner(i) == me, i = 1, nn)])
  eg = pack([(int(i, ik), i = 1, ne)], [(elem_owner(i) == me, i = 1, ne)])
  write(*, '(a,i0,a,i0,a,i0,a,i0,a,i0,a)') 'rank ', me, ' of ', np, ': ', size(ng), ' nodes in ', &
    runs(ng), ' runs, ', size(eg), ' elements'

  ! ------------------------------------------------ collective failures: the same on every rank
  call fw_open(w, trim(outdir)//'/no/such/dir/x.h5', trim(outdir)//'/no/such/dir/x.xmf', &
               int(nn, ik), int(ne, ik), ng, eg, node_id(ng), elem_id(eg), conn(eg, :), &
               part_id(eg), x0(ng, :), 'deck', 'v', 't', int(np, ik), ok, errmsg)
  call check(.not. ok .and. index(errmsg, 'no/such/dir/x.h5') > 0, 'open_bad_dir_fails_on_every_rank')
  call fw_reopen(w, trim(outdir)//'/no_such.h5', trim(outdir)//'/no_such.xmf', int(nn, ik), &
                 int(ne, ik), ng, eg, 1_ik, 't', ok, errmsg)
  call check(.not. ok .and. index(errmsg, 'no_such.h5') > 0, 'reopen_missing_fails_on_every_rank')

  ! ------------------------------------------------ write: 2 steps, close
  call fw_open(w, h5path, xmfpath, int(nn, ik), int(ne, ik), ng, eg, node_id(ng), elem_id(eg), &
               conn(eg, :), part_id(eg), x0(ng, :), 'deck text'//new_line('a')//'line 2', &
               '0.0-test', 'ranks test', int(np, ik), ok, errmsg)
  call must(ok, 'fw_open', errmsg)
  do k = 0, 1
    call write_step(k, k == 0)
  end do
  call fw_close(w)

  ! ------------------------------------------------ restart: keep step 0, redo step 1
  call fw_reopen(w, h5path, xmfpath, int(nn, ik), int(ne, ik), ng, eg, 1_ik, 'ranks test', &
                 ok, errmsg)
  call must(ok, 'fw_reopen', errmsg)
  call write_step(1, .true.)
  call fw_close(w)

  ! ------------------------------------------------ read back on rank 0
  if (comms_is_root()) call verify()
  call comms_finalize()
  if (n_fail > 0) then
    write(*, '(a,i0,a)') 'test_field_output_mpi: ', n_fail, ' failure(s)'
    error stop 1
  end if
  if (me == 0) write(*, '(a)') 'test_field_output_mpi: all passed ('//trim(tag)//')'

contains

  integer function node_owner(i)
    integer, intent(in) :: i
    node_owner = mod(7*i + 3, np)
  end function node_owner

  integer function elem_owner(e)
    integer, intent(in) :: e
    if (np < 3) then
      elem_owner = mod(7*e + 3, np)
    else
      elem_owner = 1 + mod(7*e + 3, np - 1)
    end if
  end function elem_owner

  integer function runs(g)
    integer(ik), intent(in) :: g(:)
    integer :: j
    runs = min(size(g), 1)
    do j = 2, size(g)
      if (g(j) /= g(j-1) + 1) runs = runs + 1
    end do
  end function runs

  !> Step k: coordinates, velocity, pressure and (with_mass) mass.
  subroutine write_step(kk, with_mass)
    integer, intent(in) :: kk
    logical, intent(in) :: with_mass
    call fw_begin_step(w, times(kk), int(10*kk, ik), xs(ng, :, kk), ok, errmsg)
    call must(ok, 'fw_begin_step', errmsg)
    call fw_node_vector(w, 'velocity', vel(ng, :, kk), ok, errmsg)
    call must(ok, 'fw_node_vector', errmsg)
    if (with_mass) then
      call fw_node_scalar(w, 'mass', mass(ng), ok, errmsg)
      call must(ok, 'fw_node_scalar', errmsg)
    end if
    call fw_elem_scalar(w, 'pressure', p(eg, kk), ok, errmsg)
    call must(ok, 'fw_elem_scalar', errmsg)
    call fw_end_step(w, ok, errmsg)
    call must(ok, 'fw_end_step', errmsg)
  end subroutine write_step

  !> A failed collective call leaves the other ranks waiting: end them all.
  subroutine must(cond, name, detail)
    logical, intent(in) :: cond
    character(len=*), intent(in) :: name, detail
    if (cond) return
    write(*, '(a,i0,a)') 'FAIL rank ', me, ' '//name//': '//detail
    call comms_abort(3)
  end subroutine must

  subroutine check(cond, name)
    logical, intent(in) :: cond
    character(len=*), intent(in) :: name
    if (cond) then
      write(*, '(a)') 'PASS '//name
    else
      n_fail = n_fail + 1
      write(*, '(a)') 'FAIL '//name
    end if
  end subroutine check

  !> Everything in the file, against the global arrays (read serially).
  subroutine verify()
    integer(hid_t) :: fid
    integer :: err
    integer(ik), target :: ivec(ne), ibuf(4, ne), nvec(nn), cnt
    real(rk), target :: rbuf(3, nn), rn(nn), re(ne), t
    integer(i8), target :: cyc
    logical :: ex
    character(len=6) :: g

    call h5open_f(err)
    call h5fopen_f(h5path, H5F_ACC_RDONLY_F, fid, err)
    call check(err >= 0, 'open_'//trim(tag))
    if (err < 0) return
    call read_attr(fid, 'steps', 'count', h5kind_to_type(ik, H5_INTEGER_KIND), c_loc(cnt))
    call check(cnt == 2, 'count_2')
    call h5lexists_f(fid, 'steps/000002', ex, err)
    call check(.not. ex, 'no_step_2')
    call read_ds(fid, 'mesh/node_id', h5kind_to_type(ik, H5_INTEGER_KIND), c_loc(nvec))
    call check(all(nvec == node_id), 'node_id')
    call read_ds(fid, 'mesh/elem_id', h5kind_to_type(ik, H5_INTEGER_KIND), c_loc(ivec))
    call check(all(ivec == elem_id), 'elem_id')
    call read_ds(fid, 'mesh/part_id', h5kind_to_type(ik, H5_INTEGER_KIND), c_loc(ivec))
    call check(all(ivec == part_id), 'part_id')
    call read_ds(fid, 'mesh/connectivity', h5kind_to_type(ik, H5_INTEGER_KIND), c_loc(ibuf))
    call check(all(ibuf == transpose(conn) - 1), 'connectivity_0_based')
    call read_ds(fid, 'mesh/x0', h5kind_to_type(rk, H5_REAL_KIND), c_loc(rbuf))
    call check(all(rbuf == transpose(x0)), 'x0')
    do k = 0, 1
      write(g, '(i6.6)') k
      call read_attr(fid, 'steps/'//g, 'time', h5kind_to_type(rk, H5_REAL_KIND), c_loc(t))
      call read_attr(fid, 'steps/'//g, 'cycle', h5kind_to_type(i8, H5_INTEGER_KIND), c_loc(cyc))
      call check(t == times(k) .and. cyc == 10*k, 'time_cycle_'//g)
      call read_ds(fid, 'steps/'//g//'/coordinates', h5kind_to_type(rk, H5_REAL_KIND), c_loc(rbuf))
      call check(all(rbuf == transpose(xs(:, :, k))), 'coordinates_'//g)
      call read_ds(fid, 'steps/'//g//'/velocity', h5kind_to_type(rk, H5_REAL_KIND), c_loc(rbuf))
      call check(all(rbuf == transpose(vel(:, :, k))), 'velocity_'//g)
      call read_ds(fid, 'steps/'//g//'/mass', h5kind_to_type(rk, H5_REAL_KIND), c_loc(rn))
      call check(all(rn == mass), 'mass_'//g)
      call read_ds(fid, 'steps/'//g//'/pressure', h5kind_to_type(rk, H5_REAL_KIND), c_loc(re))
      call check(all(re == p(:, k)), 'pressure_'//g)
    end do
    call h5fclose_f(fid, err)
    inquire(file=xmfpath, exist=ex)
    call check(ex, 'xmf_exists')
  end subroutine verify

  subroutine read_ds(fid, path, mtype, buf)
    integer(hid_t), intent(in) :: fid, mtype
    character(len=*), intent(in) :: path
    type(c_ptr), intent(in) :: buf
    integer(hid_t) :: did
    integer :: err
    type(c_ptr) :: q

    call h5dopen_f(fid, path, did, err)
    if (err < 0) then
      call check(.false., 'open_'//path)
      return
    end if
    q = buf
    call h5dread_f(did, mtype, q, err)
    call check(err >= 0, 'read_'//path)
    call h5dclose_f(did, err)
  end subroutine read_ds

  subroutine read_attr(fid, obj, name, mtype, buf)
    integer(hid_t), intent(in) :: fid, mtype
    character(len=*), intent(in) :: obj, name
    type(c_ptr), intent(in) :: buf
    integer(hid_t) :: aid
    integer :: err
    type(c_ptr) :: q

    call h5aopen_by_name_f(fid, obj, name, aid, err)
    if (err < 0) then
      call check(.false., 'attr_'//obj//'@'//name)
      return
    end if
    q = buf
    call h5aread_f(aid, mtype, q, err)
    call h5aclose_f(aid, err)
  end subroutine read_attr

end program test_field_output_mpi
