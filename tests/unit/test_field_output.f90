!> Unit test for udar_field_output: writes a 2-tet mesh with 2 steps, reads
!> the HDF5 file back through the HDF5 Fortran API and checks the .xmf; then
!> a restart (fw_reopen) that keeps 2 of 3 steps and writes one more.
!> One process (MPI singleton): this rank owns every node and element
!> (gidx = 1..n); test_field_output_mpi covers rows split over ranks.
!> Usage: test_field_output [<data_dir>] <output_dir>
!> The output directory is the LAST argument (tests/run_tests.sh passes
!> <tests/unit> <work dir>); it is created if missing.
program test_field_output
  use, intrinsic :: iso_c_binding, only: c_ptr, c_loc, c_f_pointer, c_char, c_size_t, &
                                         c_int, c_null_char
  use udar_kinds, only: rk, ik, i8
  use udar_field_output
  use udar_comms, only: comms_init, comms_finalize
  use hdf5
  implicit none

  interface
    function c_strlen(s) bind(c, name='strlen') result(n)
      import :: c_ptr, c_size_t
      type(c_ptr), value :: s
      integer(c_size_t) :: n
    end function c_strlen
    function c_mkdir(path, mode) bind(c, name='mkdir') result(r)
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int), value :: mode   ! mode_t is a 32-bit unsigned on Linux
      integer(c_int) :: r
    end function c_mkdir
  end interface

  integer, parameter :: nn = 5, ne = 2
  integer :: n_fail = 0
  character(len=1024) :: outdir
  character(len=:), allocatable :: h5path, xmfpath, big_deck, deck, errmsg
  type(field_writer_t) :: w
  integer(ik) :: node_id(nn), elem_id(ne), conn(ne, 4), part_id(ne), ngidx(nn), egidx(ne)
  real(rk) :: x0(nn, 3), x1(nn, 3), vel0(nn, 3), vel1(nn, 3), mass(nn), p0(ne), p1(ne)
  logical :: ok
  integer :: i, nargs
  integer(c_int) :: irc

  call comms_init()
  nargs = command_argument_count()
  if (nargs < 1) then
    call fail('args', 'usage: test_field_output [<data_dir>] <output_dir>')
    call finish()
  end if
  call get_command_argument(nargs, outdir)
  ! mkdir -p: create each component; EEXIST is fine, real failures show at fw_open
  do i = 2, len_trim(outdir)
    if (outdir(i:i) == '/') irc = c_mkdir(outdir(1:i-1)//c_null_char, int(o'755', c_int))
  end do
  irc = c_mkdir(trim(outdir)//c_null_char, int(o'755', c_int))
  h5path = trim(outdir)//'/fo_test.h5'
  xmfpath = trim(outdir)//'/fo_test.xmf'

  ! Two tets sharing face (2,3,4).
  x0(1,:) = [0.0_rk, 0.0_rk, 0.0_rk]
  x0(2,:) = [1.0_rk, 0.0_rk, 0.0_rk]
  x0(3,:) = [0.0_rk, 1.0_rk, 0.0_rk]
  x0(4,:) = [0.0_rk, 0.0_rk, 1.0_rk]
  x0(5,:) = [1.0_rk, 1.0_rk, 1.0_rk]
  node_id = [101, 102, 103, 104, 105]
  elem_id = [11, 12]
  part_id = [1, 2]
  conn(1,:) = [1, 2, 3, 4]
  conn(2,:) = [2, 3, 4, 5]
  ngidx = [(i, i = 1, nn)]
  egidx = [(i, i = 1, ne)]
  do i = 1, nn
    vel0(i,:) = [real(i, rk), 10.0_rk*i, 100.0_rk*i]
    mass(i) = 0.5_rk*i
  end do
  x1 = x0 + 0.01_rk*vel0
  vel1 = -vel0
  p0 = [1.0e5_rk, 2.0e5_rk]
  p1 = [-3.5_rk, 4.25_rk]

  ! Deck above the 64 KiB compact attribute limit, with newlines and XML
  ! metacharacters, to exercise the variable-length string path.
  deck = '# deck <test> & "quotes"'//new_line('a')//'*MAT rho=7850'//new_line('a')
  big_deck = repeat(deck, 3000)

  ! ---------------------------------------------------------- writing
  call fw_open(w, h5path, xmfpath, int(nn, ik), int(ne, ik), ngidx, egidx, node_id, elem_id, &
               conn, part_id, x0, big_deck, &
               '0.1.0-test', 'two tets <&>', 4_ik, ok, errmsg)
  call check(ok, 'fw_open', errmsg)
  if (.not. ok) call finish()

  call fw_node_scalar(w, 'mass', mass, ok, errmsg)
  call check(.not. ok, 'field_outside_step_rejected', 'accepted')

  call fw_begin_step(w, 0.0_rk, 0_ik, x0, ok, errmsg)
  call check(ok, 'begin_step_0', errmsg)
  call fw_begin_step(w, 0.0_rk, 0_ik, x0, ok, errmsg)
  call check(.not. ok, 'double_begin_rejected', 'accepted')
  call fw_node_vector(w, 'velocity', vel0, ok, errmsg)
  call check(ok, 'node_vector_0', errmsg)
  call fw_node_scalar(w, 'mass', mass, ok, errmsg)
  call check(ok, 'node_scalar_0', errmsg)
  call fw_elem_scalar(w, 'pressure', p0, ok, errmsg)
  call check(ok, 'elem_scalar_0', errmsg)
  call fw_elem_scalar(w, 'pressure', p0, ok, errmsg)
  call check(.not. ok, 'duplicate_name_rejected', 'accepted')
  call fw_elem_scalar(w, 'bad name', p0, ok, errmsg)
  call check(.not. ok, 'invalid_name_rejected', 'accepted')
  call fw_elem_scalar(w, 'part_id', p0, ok, errmsg)
  call check(.not. ok, 'reserved_name_rejected', 'accepted')
  call fw_elem_scalar(w, 'short', p0(1:1), ok, errmsg)
  call check(.not. ok, 'wrong_size_rejected', 'accepted')
  call check(index(errmsg, h5path) > 0, 'errmsg_names_file', errmsg)
  call fw_end_step(w, ok, errmsg)
  call check(ok, 'end_step_0', errmsg)
  call check(file_exists(xmfpath), 'xmf_after_step_0', 'missing '//xmfpath)

  call fw_begin_step(w, 1.5e-6_rk, 10_i8, x1, ok, errmsg)
  call check(ok, 'begin_step_1', errmsg)
  call fw_node_vector(w, 'velocity', vel1, ok, errmsg)
  call check(ok, 'node_vector_1', errmsg)
  call fw_elem_scalar(w, 'pressure', p1, ok, errmsg)
  call check(ok, 'elem_scalar_1', errmsg)
  call fw_end_step(w, ok, errmsg)
  call check(ok, 'end_step_1', errmsg)
  call fw_end_step(w, ok, errmsg)
  call check(.not. ok, 'end_without_begin_rejected', 'accepted')
  call fw_close(w)
  call fw_close(w)   ! second close is a no-op

  ! ---------------------------------------------------------- failures at open
  call fw_open(w, trim(outdir)//'/no/such/dir/x.h5', trim(outdir)//'/no/such/dir/x.xmf', &
               int(nn, ik), int(ne, ik), ngidx, egidx, &
               node_id, elem_id, conn, part_id, x0, 'deck', 'v', 't', 1_ik, ok, errmsg)
  call check(.not. ok .and. index(errmsg, 'no/such/dir/x.h5') > 0, 'open_bad_dir_reports_path', errmsg)
  call fw_open(w, trim(outdir)//'/bad_conn.h5', trim(outdir)//'/bad_conn.xmf', int(nn, ik), &
               int(ne, ik), ngidx, egidx, node_id, elem_id, &
               reshape([1_ik, 2_ik, 3_ik, 4_ik, 5_ik, 6_ik, 3_ik, 9_ik], [2, 4]), part_id, x0, &
               'deck', 'v', 't', 1_ik, ok, errmsg)
  call check(.not. ok, 'open_bad_conn_rejected', 'accepted')
  call fw_open(w, trim(outdir)//'/a.h5', trim(outdir)//'/sub/a.xmf', int(nn, ik), int(ne, ik), &
               ngidx, egidx, node_id, elem_id, conn, part_id, x0, 'deck', 'v', 't', 1_ik, ok, errmsg)
  call check(.not. ok, 'open_split_dirs_rejected', 'accepted')
  ! global indices: strictly ascending, within 1..n_global, one row each
  call fw_open(w, trim(outdir)//'/g.h5', trim(outdir)//'/g.xmf', int(nn, ik), int(ne, ik), &
               [1_ik, 2_ik, 4_ik, 3_ik, 5_ik], egidx, node_id, elem_id, conn, part_id, x0, &
               'deck', 'v', 't', 1_ik, ok, errmsg)
  call check(.not. ok .and. index(errmsg, 'ascending') > 0, 'open_gidx_not_ascending_rejected', errmsg)
  call fw_open(w, trim(outdir)//'/g.h5', trim(outdir)//'/g.xmf', int(nn, ik), int(ne, ik), &
               ngidx, [2_ik, 3_ik], node_id, elem_id, conn, part_id, x0, &
               'deck', 'v', 't', 1_ik, ok, errmsg)
  call check(.not. ok .and. index(errmsg, 'outside') > 0, 'open_gidx_out_of_range_rejected', errmsg)
  call fw_open(w, trim(outdir)//'/g.h5', trim(outdir)//'/g.xmf', int(nn, ik), int(ne, ik), &
               ngidx(1:4), egidx, node_id(1:4), elem_id, conn, part_id, x0, &
               'deck', 'v', 't', 1_ik, ok, errmsg)
  call check(.not. ok .and. index(errmsg, 'x0') > 0, 'open_x0_local_shape_rejected', errmsg)
  call fw_open(w, trim(outdir)//'/g.h5', trim(outdir)//'/g.xmf', 0_ik, int(ne, ik), &
               ngidx(1:0), egidx, node_id(1:0), elem_id, conn, part_id, x0(1:0,:), &
               'deck', 'v', 't', 1_ik, ok, errmsg)
  call check(.not. ok, 'open_zero_global_nodes_rejected', 'accepted')
  call check(.not. file_exists(trim(outdir)//'/g.h5'), 'rejected_open_creates_no_file', '')

  ! An abandoned step is unlinked at close and never counted.
  call fw_open(w, trim(outdir)//'/fo_abandon.h5', trim(outdir)//'/fo_abandon.xmf', int(nn, ik), &
               int(ne, ik), ngidx, egidx, node_id, elem_id, conn, part_id, x0, 'deck', 'v', 't', &
               1_ik, ok, errmsg)
  call check(ok, 'open_abandon', errmsg)
  call fw_begin_step(w, 0.0_rk, 0_ik, x0, ok, errmsg)
  call check(ok, 'begin_abandon', errmsg)
  call fw_close(w)

  call restart()

  ! ---------------------------------------------------------- reading back
  call verify_main()
  call verify_abandoned()
  call verify_xmf()
  call verify_restart()
  call finish()

contains

  subroutine finish()
    call comms_finalize()
    if (n_fail > 0) then
      write(*, '(a,i0,a)') 'test_field_output: ', n_fail, ' failure(s)'
      error stop 1
    end if
    write(*, '(a)') 'test_field_output: all passed'
    stop
  end subroutine finish

  !> Restart: 3 steps written, reopened keeping 2, one more step written,
  !> so the file ends with 3 steps whose last is the new one.  Also the
  !> reopen errors: missing file, too few steps, another mesh.
  subroutine restart()
    character(len=:), allocatable :: rh5, rxmf
    integer :: k

    rh5 = trim(outdir)//'/fo_restart.h5'
    rxmf = trim(outdir)//'/fo_restart.xmf'
    call fw_open(w, rh5, rxmf, int(nn, ik), int(ne, ik), ngidx, egidx, node_id, elem_id, &
                 conn, part_id, x0, 'deck', 'v', 'restart', 1_ik, ok, errmsg)
    call check(ok, 'restart_open', errmsg)
    do k = 0, 2
      call fw_begin_step(w, real(k, rk), int(10*k, ik), x0, ok, errmsg)
      if (ok .and. k == 0) call fw_node_scalar(w, 'mass', mass, ok, errmsg)
      if (ok) call fw_node_vector(w, 'velocity', vel0, ok, errmsg)
      if (ok) call fw_elem_scalar(w, 'pressure', p0, ok, errmsg)
      if (ok) call fw_end_step(w, ok, errmsg)
      call check(ok, 'restart_write_step', errmsg)
    end do
    call fw_close(w)

    call fw_reopen(w, trim(outdir)//'/no_such.h5', trim(outdir)//'/no_such.xmf', int(nn, ik), &
                   int(ne, ik), ngidx, egidx, 2_ik, 'restart', ok, errmsg)
    call check(.not. ok .and. index(errmsg, 'no_such.h5') > 0, 'reopen_missing_file_rejected', errmsg)
    call fw_reopen(w, rh5, rxmf, int(nn, ik), int(ne, ik), ngidx, egidx, 4_ik, 'restart', ok, errmsg)
    call check(.not. ok .and. index(errmsg, 'fo_restart.h5') > 0 .and. index(errmsg, 'only 3') > 0, &
               'reopen_too_few_steps_rejected', errmsg)
    call fw_reopen(w, rh5, rxmf, int(nn, ik), int(ne + 1, ik), ngidx, egidx, 2_ik, 'restart', ok, errmsg)
    call check(.not. ok .and. index(errmsg, 'fo_restart.h5') > 0, 'reopen_other_mesh_rejected', errmsg)

    call fw_reopen(w, rh5, rxmf, int(nn, ik), int(ne, ik), ngidx, egidx, 2_ik, 'restart', ok, errmsg)
    call check(ok, 'reopen_keep_2', errmsg)
    if (.not. ok) return
    call fw_begin_step(w, 9.0_rk, 99_ik, x1, ok, errmsg)
    call check(ok, 'reopen_begin_step', errmsg)
    call fw_node_vector(w, 'velocity', vel1, ok, errmsg)
    call check(ok, 'reopen_node_vector', errmsg)
    call fw_elem_scalar(w, 'pressure', p1, ok, errmsg)
    call check(ok, 'reopen_elem_scalar', errmsg)
    call fw_end_step(w, ok, errmsg)
    call check(ok, 'reopen_end_step', errmsg)
    call fw_close(w)
    call restart_square()
  end subroutine restart

  !> A mesh with as many nodes as elements: a 1-D field could be either;
  !> fw_reopen takes the Center from the .xmf it replaces.
  subroutine restart_square()
    character(len=:), allocatable :: sh5, sxmf
    integer(ik) :: g(nn), c(nn, 4)
    integer :: u, ios
    character(len=4096) :: line
    logical :: node_ok, cell_ok

    sh5 = trim(outdir)//'/fo_square.h5'
    sxmf = trim(outdir)//'/fo_square.xmf'
    g = [(int(i, ik), i = 1, nn)]
    c = 1
    c(:, 2) = 2; c(:, 3) = 3; c(:, 4) = g
    call fw_open(w, sh5, sxmf, int(nn, ik), int(nn, ik), g, g, node_id, node_id, c, g, x0, &
                 'deck', 'v', 'square', 1_ik, ok, errmsg)
    if (ok) call fw_begin_step(w, 0.0_rk, 0_ik, x0, ok, errmsg)
    if (ok) call fw_elem_scalar(w, 'es', mass, ok, errmsg)
    if (ok) call fw_node_scalar(w, 'ns', mass, ok, errmsg)
    if (ok) call fw_end_step(w, ok, errmsg)
    call fw_close(w)
    call check(ok, 'square_write', errmsg)
    call fw_reopen(w, sh5, sxmf, int(nn, ik), int(nn, ik), g, g, 1_ik, 'square', ok, errmsg)
    call check(ok, 'square_reopen', errmsg)
    call fw_close(w)
    node_ok = .false.; cell_ok = .false.
    open(newunit=u, file=sxmf, status='old', action='read', iostat=ios)
    do while (ios == 0)
      read(u, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (index(line, '<Attribute Name="ns" AttributeType="Scalar" Center="Node">') > 0) node_ok = .true.
      if (index(line, '<Attribute Name="es" AttributeType="Scalar" Center="Cell">') > 0) cell_ok = .true.
    end do
    close(u, iostat=ios)
    call check(node_ok .and. cell_ok, 'square_reopen_keeps_centers', sxmf)
  end subroutine restart_square

  subroutine verify_restart()
    integer(hid_t) :: fid
    integer :: err, u, ios, n_uniform
    logical :: ex, step0_mass_node, pressure_cell, new_time
    real(rk) :: t
    integer(i8) :: cyc
    real(rk), allocatable, target :: rbuf(:,:)
    character(len=4096) :: line

    call h5fopen_f(trim(outdir)//'/fo_restart.h5', H5F_ACC_RDONLY_F, fid, err)
    call check(err >= 0, 'reopen_restart_h5', '')
    if (err < 0) return
    call check(read_attr_int(fid, 'steps', 'count') == 3, 'restart_count_3', '')
    call h5lexists_f(fid, 'steps/000003', ex, err)
    call check(.not. ex, 'restart_no_step_3', '')
    call read_step_attrs(fid, 'steps/000001', t, cyc)
    call check(t == 1.0_rk .and. cyc == 10, 'restart_step1_kept', '')
    call read_step_attrs(fid, 'steps/000002', t, cyc)
    call check(t == 9.0_rk .and. cyc == 99, 'restart_step2_new_time', '')
    allocate(rbuf(3, nn))
    call read_raw(fid, 'steps/000002/velocity', h5kind_to_type(rk, H5_REAL_KIND), c_loc(rbuf))
    call check(all(rbuf == transpose(vel1)), 'restart_step2_new_velocity', '')
    call read_raw(fid, 'steps/000002/coordinates', h5kind_to_type(rk, H5_REAL_KIND), c_loc(rbuf))
    call check(all(rbuf == transpose(x1)), 'restart_step2_new_coords', '')
    call h5fclose_f(fid, err)

    n_uniform = 0
    step0_mass_node = .false.; pressure_cell = .false.; new_time = .false.
    open(newunit=u, file=trim(outdir)//'/fo_restart.xmf', status='old', action='read', iostat=ios)
    call check(ios == 0, 'restart_xmf_exists', '')
    if (ios /= 0) return
    do
      read(u, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (index(line, '<Grid') > 0 .and. index(line, 'GridType="Uniform"') > 0) &
        n_uniform = n_uniform + 1
      if (index(line, '<Attribute Name="mass" AttributeType="Scalar" Center="Node">') > 0) &
        step0_mass_node = .true.
      if (index(line, '<Attribute Name="pressure" AttributeType="Scalar" Center="Cell">') > 0) &
        pressure_cell = .true.
      if (index(line, '<Time Value="9.') > 0) new_time = .true.
    end do
    close(u)
    call check(n_uniform == 3, 'restart_xmf_lists_3_steps', '')
    call check(new_time, 'restart_xmf_has_new_time', '')
    call check(step0_mass_node .and. pressure_cell, 'restart_xmf_rebuilt_centers', '')
    call check(.not. file_exists(trim(outdir)//'/fo_restart.xmf.tmp'), 'restart_xmf_tmp_removed', '')
  end subroutine verify_restart

  subroutine check(cond, name, detail)
    logical, intent(in) :: cond
    character(len=*), intent(in) :: name
    character(len=*), intent(in) :: detail
    if (cond) then
      write(*, '(a)') 'PASS '//name
    else
      call fail(name, detail)
    end if
  end subroutine check

  subroutine fail(name, detail)
    character(len=*), intent(in) :: name, detail
    n_fail = n_fail + 1
    write(*, '(a)') 'FAIL '//name//': '//detail
  end subroutine fail

  logical function file_exists(path)
    character(len=*), intent(in) :: path
    inquire(file=path, exist=file_exists)
  end function file_exists

  subroutine verify_main()
    integer(hid_t) :: fid
    integer :: err
    integer(ik), allocatable, target :: ibuf(:,:), ivec(:)
    real(rk), allocatable, target :: rbuf(:,:), rvec(:)
    character(len=:), allocatable :: s
    logical :: ex
    real(rk) :: t
    integer(i8) :: cyc
    integer(hsize_t), allocatable :: dims(:)

    ! Reals are compared with == on purpose: storage is lossless float64.
    call h5open_f(err)
    call h5fopen_f(h5path, H5F_ACC_RDONLY_F, fid, err)
    call check(err >= 0, 'reopen_h5', h5path)
    if (err < 0) return

    ! Root attributes
    call check(read_attr_int(fid, '.', 'n_nodes') == nn, 'attr_n_nodes', '')
    call check(read_attr_int(fid, '.', 'n_elems') == ne, 'attr_n_elems', '')
    s = read_attr_str(fid, '.', 'program')
    call check(s == 'udar', 'attr_program', s)
    s = read_attr_str(fid, '.', 'version')
    call check(s == '0.1.0-test', 'attr_version', s)
    s = read_attr_str(fid, '.', 'title')
    call check(s == 'two tets <&>', 'attr_title', s)
    s = read_attr_str(fid, '.', 'deck')
    call check(s == big_deck, 'attr_deck_roundtrip', 'deck differs')
    call check(read_attr_int(fid, 'provenance', 'n_ranks') == 4, 'prov_n_ranks', '')
    s = read_attr_str(fid, 'provenance', 'created')
    call check(len(s) >= 19 .and. s(5:5) == '-' .and. s(11:11) == 'T', 'prov_created_iso8601', s)
    call h5aexists_by_name_f(fid, '.', 'n_ranks', ex, err)
    call check(.not. ex, 'no_provenance_at_root', 'n_ranks at root')

    ! Mesh
    dims = ds_dims(fid, 'mesh/node_id')
    call check(same(dims, [int(nn, hsize_t)]), 'node_id_shape', '')
    allocate(ivec(nn))
    call read_raw(fid, 'mesh/node_id', h5kind_to_type(ik, H5_INTEGER_KIND), c_loc(ivec))
    call check(all(ivec == node_id), 'node_id_values', '')
    deallocate(ivec); allocate(ivec(ne))
    call read_raw(fid, 'mesh/elem_id', h5kind_to_type(ik, H5_INTEGER_KIND), c_loc(ivec))
    call check(all(ivec == elem_id), 'elem_id_values', '')
    call read_raw(fid, 'mesh/part_id', h5kind_to_type(ik, H5_INTEGER_KIND), c_loc(ivec))
    call check(all(ivec == part_id), 'part_id_values', '')
    ! Fortran dims are reversed: (4,ne) here is C-order (ne,4).
    dims = ds_dims(fid, 'mesh/connectivity')
    call check(same(dims, [4_hsize_t, int(ne, hsize_t)]), 'connectivity_shape_C_ne_4', '')
    allocate(ibuf(4, ne))
    call read_raw(fid, 'mesh/connectivity', h5kind_to_type(ik, H5_INTEGER_KIND), c_loc(ibuf))
    call check(all(ibuf == transpose(conn) - 1), 'connectivity_0_based', '')
    call check(minval(ibuf) == 0 .and. maxval(ibuf) == nn - 1, 'connectivity_range', '')
    dims = ds_dims(fid, 'mesh/x0')
    call check(same(dims, [3_hsize_t, int(nn, hsize_t)]), 'x0_shape_C_nn_3', '')
    allocate(rbuf(3, nn))
    call read_raw(fid, 'mesh/x0', h5kind_to_type(rk, H5_REAL_KIND), c_loc(rbuf))
    call check(all(rbuf == transpose(x0)), 'x0_values', '')

    ! Steps
    call check(read_attr_int(fid, 'steps', 'count') == 2, 'steps_count', '')
    call h5lexists_f(fid, 'steps/000002', ex, err)
    call check(.not. ex, 'no_extra_step', '')

    call read_step_attrs(fid, 'steps/000000', t, cyc)
    call check(t == 0.0_rk .and. cyc == 0, 'step0_time_cycle', '')
    call read_step_attrs(fid, 'steps/000001', t, cyc)
    call check(t == 1.5e-6_rk .and. cyc == 10, 'step1_time_cycle', '')

    dims = ds_dims(fid, 'steps/000000/coordinates')
    call check(same(dims, [3_hsize_t, int(nn, hsize_t)]), 'coords_shape_C_nn_3', '')
    call read_raw(fid, 'steps/000000/coordinates', h5kind_to_type(rk, H5_REAL_KIND), c_loc(rbuf))
    call check(all(rbuf == transpose(x0)), 'step0_coords', '')
    call read_raw(fid, 'steps/000001/coordinates', h5kind_to_type(rk, H5_REAL_KIND), c_loc(rbuf))
    call check(all(rbuf == transpose(x1)), 'step1_coords', '')
    dims = ds_dims(fid, 'steps/000001/velocity')
    call check(same(dims, [3_hsize_t, int(nn, hsize_t)]), 'velocity_shape_C_nn_3', '')
    call read_raw(fid, 'steps/000000/velocity', h5kind_to_type(rk, H5_REAL_KIND), c_loc(rbuf))
    call check(all(rbuf == transpose(vel0)), 'step0_velocity', '')
    ! Element 1 in row 1 of the C-order array: (x,y,z) of node 2 contiguous.
    call check(rbuf(1,2) == 2.0_rk .and. rbuf(2,2) == 20.0_rk .and. rbuf(3,2) == 200.0_rk, &
               'velocity_row_layout', '')
    call read_raw(fid, 'steps/000001/velocity', h5kind_to_type(rk, H5_REAL_KIND), c_loc(rbuf))
    call check(all(rbuf == transpose(vel1)), 'step1_velocity', '')

    allocate(rvec(nn))
    dims = ds_dims(fid, 'steps/000000/mass')
    call check(same(dims, [int(nn, hsize_t)]), 'mass_shape', '')
    call read_raw(fid, 'steps/000000/mass', h5kind_to_type(rk, H5_REAL_KIND), c_loc(rvec))
    call check(all(rvec == mass), 'step0_mass', '')
    call h5lexists_f(fid, 'steps/000001/mass', ex, err)
    call check(.not. ex, 'step1_has_no_mass', '')
    deallocate(rvec); allocate(rvec(ne))
    dims = ds_dims(fid, 'steps/000000/pressure')
    call check(same(dims, [int(ne, hsize_t)]), 'pressure_shape', '')
    call read_raw(fid, 'steps/000000/pressure', h5kind_to_type(rk, H5_REAL_KIND), c_loc(rvec))
    call check(all(rvec == p0), 'step0_pressure', '')
    call read_raw(fid, 'steps/000001/pressure', h5kind_to_type(rk, H5_REAL_KIND), c_loc(rvec))
    call check(all(rvec == p1), 'step1_pressure', '')

    call h5fclose_f(fid, err)
  end subroutine verify_main

  subroutine verify_abandoned()
    integer(hid_t) :: fid
    integer :: err
    logical :: ex
    call h5fopen_f(trim(outdir)//'/fo_abandon.h5', H5F_ACC_RDONLY_F, fid, err)
    call check(err >= 0, 'reopen_abandon', '')
    if (err < 0) return
    call check(read_attr_int(fid, 'steps', 'count') == 0, 'abandon_count_0', '')
    call h5lexists_f(fid, 'steps/000000', ex, err)
    call check(.not. ex, 'abandoned_step_unlinked', '')
    call h5fclose_f(fid, err)
    call check(.not. file_exists(trim(outdir)//'/fo_abandon.xmf'), 'abandon_no_xmf', '')
  end subroutine verify_abandoned

  subroutine verify_xmf()
    integer :: u, ios, n_uniform, n_time
    character(len=4096) :: line
    logical :: rel_ok, abs_seen

    call check(file_exists(xmfpath), 'xmf_exists', xmfpath)
    call check(.not. file_exists(xmfpath//'.tmp'), 'xmf_tmp_removed', '')
    open(newunit=u, file=xmfpath, status='old', action='read', iostat=ios)
    if (ios /= 0) return
    n_uniform = 0; n_time = 0
    rel_ok = .false.; abs_seen = .false.
    do
      read(u, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (index(line, '<Grid') > 0 .and. index(line, 'GridType="Uniform"') > 0) &
        n_uniform = n_uniform + 1
      if (index(line, '<Time Value=') > 0) n_time = n_time + 1
      if (index(line, '>fo_test.h5:/mesh/connectivity<') > 0) rel_ok = .true.
      if (index(line, trim(outdir)//'/fo_test.h5') > 0) abs_seen = .true.
    end do
    close(u)
    call check(n_uniform == 2, 'xmf_two_step_grids', '')
    call check(n_time == 2, 'xmf_two_times', '')
    call check(rel_ok .and. .not. abs_seen, 'xmf_relative_h5_ref', '')
  end subroutine verify_xmf

  logical function same(a, b)
    integer(hsize_t), intent(in) :: a(:), b(:)
    same = size(a) == size(b)
    if (same) same = all(a == b)
  end function same

  function ds_dims(fid, path) result(dims)
    integer(hid_t), intent(in) :: fid
    character(len=*), intent(in) :: path
    integer(hsize_t), allocatable :: dims(:)
    integer(hsize_t) :: d(8), m(8)
    integer(hid_t) :: did, sid
    integer :: err, rank

    allocate(dims(0))
    call h5dopen_f(fid, path, did, err)
    if (err < 0) then
      call fail('open '//path, 'h5dopen_f failed')
      return
    end if
    call h5dget_space_f(did, sid, err)
    call h5sget_simple_extent_ndims_f(sid, rank, err)
    call h5sget_simple_extent_dims_f(sid, d(1:rank), m(1:rank), err)
    dims = d(1:rank)
    call h5sclose_f(sid, err)
    call h5dclose_f(did, err)
  end function ds_dims

  !> Read a whole dataset into a contiguous buffer of the given memory type.
  subroutine read_raw(fid, path, mtype, buf)
    integer(hid_t), intent(in) :: fid, mtype
    character(len=*), intent(in) :: path
    type(c_ptr), intent(in) :: buf
    integer(hid_t) :: did
    integer :: err
    type(c_ptr) :: p   ! h5dread_f wants a definable c_ptr

    call h5dopen_f(fid, path, did, err)
    if (err < 0) then
      call fail('read '//path, 'h5dopen_f failed')
      return
    end if
    p = buf
    call h5dread_f(did, mtype, p, err)
    if (err < 0) call fail('read '//path, 'h5dread_f failed')
    call h5dclose_f(did, err)
  end subroutine read_raw

  !> Read the scalar attribute obj@name into the buffer at buf (memory type
  !> mtype). found: it exists; ok: it was read.
  subroutine read_attr(fid, obj, name, mtype, buf, found, ok)
    integer(hid_t), intent(in) :: fid, mtype
    character(len=*), intent(in) :: obj, name
    type(c_ptr), intent(in) :: buf
    logical, intent(out) :: found, ok
    integer(hid_t) :: aid
    integer :: err
    type(c_ptr) :: p   ! h5aread_f wants a definable c_ptr

    ok = .false.
    call h5aopen_by_name_f(fid, obj, name, aid, err)
    found = err >= 0
    if (.not. found) return
    p = buf
    call h5aread_f(aid, mtype, p, err)
    ok = err >= 0
    call h5aclose_f(aid, err)
  end subroutine read_attr

  integer function read_attr_int(fid, obj, name) result(v)
    integer(hid_t), intent(in) :: fid
    character(len=*), intent(in) :: obj, name
    integer(ik), target :: tmp
    logical :: found, ok

    v = -huge(1)
    call read_attr(fid, obj, name, h5kind_to_type(ik, H5_INTEGER_KIND), c_loc(tmp), found, ok)
    if (.not. found) call fail('attr '//obj//'@'//name, 'missing')
    if (ok) v = tmp
  end function read_attr_int

  subroutine read_step_attrs(fid, grp, t, cyc)
    integer(hid_t), intent(in) :: fid
    character(len=*), intent(in) :: grp
    real(rk), intent(out) :: t
    integer(i8), intent(out) :: cyc
    real(rk), target :: tt
    integer(i8), target :: cc
    logical :: found, ok

    tt = -1; cc = -1
    call read_attr(fid, grp, 'time', h5kind_to_type(rk, H5_REAL_KIND), c_loc(tt), found, ok)
    call read_attr(fid, grp, 'cycle', h5kind_to_type(i8, H5_INTEGER_KIND), c_loc(cc), found, ok)
    t = tt; cyc = cc
  end subroutine read_step_attrs

  !> Read a scalar variable-length string attribute.
  function read_attr_str(fid, obj, name) result(s)
    integer(hid_t), intent(in) :: fid
    character(len=*), intent(in) :: obj, name
    character(len=:), allocatable :: s
    type(c_ptr), target :: rp(1)
    type(c_ptr) :: f_ptr
    character(kind=c_char), pointer :: chars(:)
    integer(hid_t) :: aid, tid, sid
    integer :: err, i, n
    logical :: is_vl

    s = '<unreadable>'
    call h5aopen_by_name_f(fid, obj, name, aid, err)
    if (err < 0) then
      call fail('attr '//obj//'@'//name, 'missing')
      return
    end if
    call h5aget_type_f(aid, tid, err)
    call h5tis_variable_str_f(tid, is_vl, err)
    call h5tclose_f(tid, err)
    if (.not. is_vl) then
      call fail('attr '//obj//'@'//name, 'not a variable-length string')
      call h5aclose_f(aid, err)
      return
    end if
    ! Memory type must carry the file's UTF-8 cset: HDF5 does not convert.
    call h5tcopy_f(H5T_STRING, tid, err)
    call h5tset_cset_f(tid, H5T_CSET_UTF8_F, err)
    f_ptr = c_loc(rp)
    call h5aread_f(aid, tid, f_ptr, err)
    if (err >= 0) then
      n = int(c_strlen(rp(1)))
      call c_f_pointer(rp(1), chars, [n])
      s = repeat(" ", n)
      do i = 1, n
        s(i:i) = chars(i)
      end do
      call h5aget_space_f(aid, sid, err)
      call h5dvlen_reclaim_f(tid, sid, H5P_DEFAULT_F, f_ptr, err)
      call h5sclose_f(sid, err)
    end if
    call h5tclose_f(tid, err)
    call h5aclose_f(aid, err)
  end function read_attr_str

end program test_field_output
