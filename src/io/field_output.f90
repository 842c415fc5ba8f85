!> Time-series field output: one HDF5 file plus an XDMF (.xmf) index that
!> ParaView opens directly.  Layout is specified in doc/output-format.md;
!> Python readers depend on it, so change both together.
!>
!> Parallel and collective: every rank calls every routine (MPI-IO driver,
!> collective data transfers).  Each rank passes only the rows it owns, named
!> by their 1-based global indices (node_gidx, elem_gidx: strictly ascending;
!> over all ranks each global row exactly once; a rank may own none), and
!> writes them through a hyperslab selection of the global dataset, so the
!> file content does not depend on the number of ranks (only /provenance
!> does).  Attributes and groups are metadata: every rank creates them with
!> the same values.  The .xmf index is written by rank 0 only.
!> No MPI is used here: the communicator reaches HDF5 as an integer handle
!> from udar_comms.
!>
!> Errors: failures of collective HDF5 operations (create, open, flush) and
!> of dataset writes (each rank's rows: agreed with a global minimum) are
!> reported on every rank alike.  A failed argument check is seen only by
!> the rank whose arguments are wrong, and a failed .xmf write only by rank
!> 0; the other ranks go on into the next collective call, so treat any
!> ok=.false. as fatal for the run (comms_abort ends every rank).
!>
!> Life cycle:
!>   fw_open (new file) or fw_reopen (restart: keep the first steps of an
!>   existing file) -> { fw_begin_step -> fw_node_vector/fw_node_scalar/
!>   fw_elem_scalar -> fw_end_step }* -> fw_close
!> A step is committed (counted in /steps@count and listed in the .xmf) only
!> by fw_end_step.
module udar_field_output
  use, intrinsic :: iso_c_binding, only: c_char, c_int, c_int64_t, c_ptr, c_loc, c_null_char
  use udar_kinds, only: rk, ik, i8, max_name_len
  use udar_strings, only: is_letter, is_digit, dir_name, base_name, itoa
  use udar_comms, only: comms_world_handle, comms_info_null_handle, comms_is_root, comms_min_int
  use udar_files, only: rename_file, remove_if_present
  use hdf5
  implicit none
  private

  public :: fw_open, fw_reopen, fw_begin_step, fw_node_vector, fw_node_scalar, &
            fw_elem_scalar, fw_particles, fw_end_step, fw_close

  !> The particles' scalar fields (fw_particles; /steps/NNNNNN/particles/...)
  character(len=*), parameter, public :: particle_scalars(10) = [character(len=24) :: 'mass', 'density', 'pressure', &
      'specific_internal_energy', 'temperature', 'plastic_strain', 'part_id', 'element', 'von_mises', 'strength_kept']

  ! Field kinds, used to pick Center/AttributeType in the XDMF.
  integer, parameter :: fk_node_vector = 1, fk_node_scalar = 2, fk_elem_scalar = 3

  integer, parameter :: step_digits = 6

  type :: field_rec_t
    character(len=max_name_len) :: name = ''
    integer :: kind = 0
  end type field_rec_t

  type :: step_rec_t
    real(rk) :: time = 0.0_rk
    integer(i8) :: cycle = 0_i8
    character(len=step_digits) :: group = ''
    integer :: n_fields = 0
    type(field_rec_t), allocatable :: fields(:)
    integer :: n_particles = -1            !< particles written with the step (-1: none, no group)
  end type step_rec_t

  !> The rows of one kind (nodes or elements) this rank writes: runs of
  !> consecutive global rows, the union of which is its file selection.
  !> The dataspaces are built on first use and kept until fw_close, one per
  !> row width (0: 1-D dataset, 3: (n,3), 4: (n,4)).
  type :: rows_t
    integer :: n = 0                              ! local rows
    integer(hsize_t) :: n_global = 0              ! rows of the dataset
    integer :: n_runs = 0
    integer(hsize_t), allocatable :: first(:)     ! 0-based first global row of each run
    integer(hsize_t), allocatable :: count(:)     ! rows in each run
    integer(hid_t) :: fspace(0:4) = -1            ! global extent, this rank's rows selected
    integer(hid_t) :: mspace(0:4) = -1            ! the local rows in memory
  end type rows_t

  ! which rows a dataset has
  integer, parameter :: on_nodes = 1, on_elems = 2

  type, public :: field_writer_t
    private
    logical :: is_open = .false.
    logical :: in_step = .false.
    integer(hid_t) :: file_id = -1
    integer(hid_t) :: dxpl = -1            ! collective data transfer property list
    integer(hid_t) :: step_gid = -1        ! group of the step being written
    character(len=:), allocatable :: h5_path, xmf_path
    character(len=:), allocatable :: h5_ref ! h5 base name, as referenced from the .xmf
    character(len=:), allocatable :: title
    integer(ik) :: n_nodes = 0, n_elems = 0 ! global
    integer :: corners = 4                  ! nodes per element: 4 tetrahedra, 3 triangles (2D)
    type(rows_t) :: node_rows, elem_rows    ! this rank's part
    integer :: n_steps = 0                  ! committed steps
    type(step_rec_t), allocatable :: steps(:)
    type(step_rec_t) :: cur                 ! step being written
    real(rk), allocatable :: buf(:,:)       ! (3,local nodes) transpose buffer
  end type field_writer_t

  !> cycle may be a default (int32) or int64 counter; stored as int64.
  interface fw_begin_step
    module procedure fw_begin_step_ik, fw_begin_step_i8
  end interface fw_begin_step

  interface
    !> Not in the Fortran API of HDF5 1.10: the union (op H5S_SELECT_OR) of
    !> two hyperslab selections as a new dataspace, negative on failure.
    !> hid_t is int64_t in C since HDF5 1.10 (and integer(hid_t) the same).
    function h5scombine_select_c(space1, op, space2) bind(c, name='H5Scombine_select') result(r)
      import :: c_int, c_int64_t
      integer(c_int64_t), value :: space1, space2
      integer(c_int), value :: op
      integer(c_int64_t) :: r
    end function h5scombine_select_c
  end interface

contains

  ! ---------------------------------------------------------------- public

  !> Create (truncate) the HDF5 file and write the run header and the mesh.
  !> Collective.  node_gidx/elem_gidx: 1-based global indices of the rows
  !> this rank writes, strictly ascending; node_id(:) and x0(:,3) hold the
  !> rows of those nodes, elem_id(:), part_id(:) and conn(:,4) (2D: conn(:,3)) those of the
  !> elements, conn with 1-based GLOBAL node indices (stored 0-based).
  !> Removes a stale .xmf of the same name: the .xmf appears at the first
  !> fw_end_step and always lists only committed steps.
  subroutine fw_open(w, h5_path, xmf_path, n_nodes_global, n_elems_global, node_gidx, elem_gidx, &
                     node_id, elem_id, conn, part_id, x0, deck_text, version, title, n_ranks, &
                     ok, errmsg)
    type(field_writer_t), intent(inout) :: w
    character(len=*), intent(in) :: h5_path, xmf_path
    integer(ik), intent(in) :: n_nodes_global, n_elems_global
    integer(ik), intent(in) :: node_gidx(:), elem_gidx(:)
    integer(ik), intent(in) :: node_id(:), elem_id(:), conn(:,:), part_id(:)
    real(rk), intent(in) :: x0(:,:)
    character(len=*), intent(in) :: deck_text, version, title
    integer(ik), intent(in) :: n_ranks
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg

    integer :: nn, ne, i, j
    integer(hid_t) :: gid
    integer(ik), allocatable :: ibuf(:,:)
    type(rows_t) :: nrows, erows

    ok = .false.
    nn = size(node_gidx)
    ne = size(elem_gidx)
    ! the first problem with the call, if any; the rank-independent ones first
    errmsg = common_arg_error(w, 'fw_open', h5_path, xmf_path, n_nodes_global, n_elems_global)
    if (len(errmsg) == 0) call make_rows(node_gidx, n_nodes_global, 'node_gidx', nrows, errmsg)
    if (len(errmsg) == 0) call make_rows(elem_gidx, n_elems_global, 'elem_gidx', erows, errmsg)
    if (len(errmsg) > 0) then
      continue
    else if (size(node_id) /= nn) then
      errmsg = 'field_output: node_id must have size(node_gidx) rows'
    else if (size(elem_id) /= ne) then
      errmsg = 'field_output: elem_id must have size(elem_gidx) rows'
    else if (size(conn, 1) /= ne .or. (size(conn, 2) /= 4 .and. size(conn, 2) /= 3)) then
      errmsg = 'field_output: conn must have shape (size(elem_gidx),4) or (size(elem_gidx),3)'
    else if (size(part_id) /= ne) then
      errmsg = 'field_output: part_id must have size(elem_gidx) rows'
    else if (any(shape(x0) /= [nn, 3])) then
      errmsg = 'field_output: x0 must have shape (size(node_gidx),3)'
    else if (any(conn < 1) .or. any(conn > n_nodes_global)) then
      errmsg = 'field_output: conn holds node indices outside 1..n_nodes_global'
    end if
    if (len(errmsg) > 0) return

    call init_writer(w, h5_path, xmf_path, title, n_nodes_global, n_elems_global, nrows, erows)
    w%corners = size(conn, 2)

    call open_file(w, .true., ok, errmsg)
    if (.not. ok) return

    ! Stale index files from an earlier run would point at the new h5.
    if (comms_is_root()) then
      call remove_if_present(w%xmf_path)
      call remove_if_present(w%xmf_path//'.tmp')
    end if

    ! A named block gives one cleanup path for every failure below.
    setup: block
      ! Root attributes: run identity only (no provenance, see below).
      call attr_str(w, w%file_id, 'program', 'udar', ok, errmsg); if (.not. ok) exit setup
      call attr_str(w, w%file_id, 'version', version, ok, errmsg); if (.not. ok) exit setup
      call attr_str(w, w%file_id, 'title', title, ok, errmsg); if (.not. ok) exit setup
      call attr_str(w, w%file_id, 'deck', deck_text, ok, errmsg); if (.not. ok) exit setup
      call attr_num(w, w%file_id, 'n_nodes', w%n_nodes, ok, errmsg); if (.not. ok) exit setup
      call attr_num(w, w%file_id, 'n_elems', w%n_elems, ok, errmsg); if (.not. ok) exit setup

      ! Provenance is isolated in one group so runs on different rank counts
      ! compare equal once this group is skipped.
      call make_group(w, w%file_id, 'provenance', gid, ok, errmsg); if (.not. ok) exit setup
      call attr_num(w, gid, 'n_ranks', n_ranks, ok, errmsg)
      if (ok) call attr_str(w, gid, 'created', iso8601_now(), ok, errmsg)
      call end_group(w, gid, 'provenance', ok, errmsg); if (.not. ok) exit setup

      ! Mesh
      call make_group(w, w%file_id, 'mesh', gid, ok, errmsg); if (.not. ok) exit setup
      call write_data(w, gid, 'node_id', on_nodes, 0, ok, errmsg, ints=node_id)
      if (ok) call write_data(w, gid, 'elem_id', on_elems, 0, ok, errmsg, ints=elem_id)
      if (ok) call write_data(w, gid, 'part_id', on_elems, 0, ok, errmsg, ints=part_id)
      if (ok) then
        ! 0-based and transposed: C-order (n_elems,corners) is what XDMF reads.
        allocate(ibuf(w%corners, ne))
        do j = 1, w%corners
          do i = 1, ne
            ibuf(j, i) = conn(i, j) - 1_ik
          end do
        end do
        call write_data(w, gid, 'connectivity', on_elems, w%corners, ok, errmsg, ints=ibuf)
        deallocate(ibuf)
      end if
      if (ok) call write_vector(w, gid, 'x0', x0, ok, errmsg)
      call end_group(w, gid, 'mesh', ok, errmsg); if (.not. ok) exit setup

      call make_group(w, w%file_id, 'steps', gid, ok, errmsg); if (.not. ok) exit setup
      call attr_num(w, gid, 'count', 0_ik, ok, errmsg)
      call end_group(w, gid, 'steps', ok, errmsg); if (.not. ok) exit setup

      call flush_file(w, ok, errmsg); if (.not. ok) exit setup
      return
    end block setup

    ! Leave the writer closed on failure so the caller can retry or abort.
    ok = .false.
    call fw_close(w)
  end subroutine fw_open

  !> Restart: open the EXISTING file h5_path read-write (collective), keep
  !> its first keep_steps committed steps and drop the rest (groups
  !> /steps/NNNNNN with NNNNNN >= keep_steps, including a partial one left
  !> by a crash), set /steps@count = keep_steps and rewrite the .xmf.  The
  !> next fw_begin_step writes step keep_steps.  The header, /mesh and
  !> /provenance are left as they are.  The mesh sizes in the file must be
  !> n_nodes_global and n_elems_global; node_gidx/elem_gidx as for fw_open.
  subroutine fw_reopen(w, h5_path, xmf_path, n_nodes_global, n_elems_global, node_gidx, elem_gidx, &
                       keep_steps, title, ok, errmsg, corners)
    type(field_writer_t), intent(inout) :: w
    character(len=*), intent(in) :: h5_path, xmf_path
    integer(ik), intent(in) :: n_nodes_global, n_elems_global
    integer(ik), intent(in) :: node_gidx(:), elem_gidx(:)
    integer(ik), intent(in) :: keep_steps
    character(len=*), intent(in) :: title
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer, intent(in), optional :: corners   !< nodes per element (default 4), as fw_open had them

    type(rows_t) :: nrows, erows
    type(step_rec_t) :: rec
    integer(ik), target :: nn_file, ne_file, count
    integer(hid_t) :: gid
    integer :: err, s, k, n_drop
    character(len=step_digits), allocatable :: drop(:)
    logical :: exists

    ok = .false.
    errmsg = common_arg_error(w, 'fw_reopen', h5_path, xmf_path, n_nodes_global, n_elems_global)
    if (len(errmsg) == 0 .and. keep_steps < 0) &
      errmsg = 'field_output: fw_reopen: keep_steps must not be negative'
    if (len(errmsg) == 0) call make_rows(node_gidx, n_nodes_global, 'node_gidx', nrows, errmsg)
    if (len(errmsg) == 0) call make_rows(elem_gidx, n_elems_global, 'elem_gidx', erows, errmsg)
    if (len(errmsg) > 0) return
    inquire(file=trim(h5_path), exist=exists)
    if (.not. exists) then
      errmsg = 'field_output: cannot reopen "'//trim(h5_path)//'": no such file'
      return
    end if

    call init_writer(w, h5_path, xmf_path, title, n_nodes_global, n_elems_global, nrows, erows)
    if (present(corners)) w%corners = corners
    call open_file(w, .false., ok, errmsg)
    if (.not. ok) return

    restore: block
      ! The file must hold this mesh.
      call read_attr(w, w%file_id, '.', 'n_nodes', h5kind_to_type(ik, H5_INTEGER_KIND), &
                     c_loc(nn_file), ok, errmsg); if (.not. ok) exit restore
      call read_attr(w, w%file_id, '.', 'n_elems', h5kind_to_type(ik, H5_INTEGER_KIND), &
                     c_loc(ne_file), ok, errmsg); if (.not. ok) exit restore
      if (nn_file /= w%n_nodes .or. ne_file /= w%n_elems) then
        ok = .false.
        errmsg = 'field_output: cannot reopen "'//w%h5_path//'": it holds a mesh of '// &
                 itoa(nn_file)//' nodes and '//itoa(ne_file)//' elements, the run has '// &
                 itoa(w%n_nodes)//' nodes and '//itoa(w%n_elems)//' elements'
        exit restore
      end if
      call read_attr(w, w%file_id, 'steps', 'count', h5kind_to_type(ik, H5_INTEGER_KIND), &
                     c_loc(count), ok, errmsg); if (.not. ok) exit restore
      if (count < keep_steps) then
        ok = .false.
        errmsg = 'field_output: cannot reopen "'//w%h5_path//'" keeping '//itoa(keep_steps)// &
                 ' steps: it holds only '//itoa(count)//' committed steps'
        exit restore
      end if

      ! Records of the kept steps (what write_xmf needs), read before the
      ! file is changed so that a bad file is left as it was.
      allocate(w%steps(max(16, 2*keep_steps)))
      do s = 1, keep_steps
        call read_step_rec(w, s - 1, rec, ok, errmsg); if (.not. ok) exit restore
        w%steps(s) = rec
      end do

      ! Drop every step group numbered keep_steps or above.
      call h5gopen_f(w%file_id, 'steps', gid, err)
      if (err < 0) then
        ok = .false.
        errmsg = op_err(w, 'open group /steps')
        exit restore
      end if
      call list_step_groups(w, gid, keep_steps, drop, n_drop, ok, errmsg)
      do k = 1, n_drop
        if (.not. ok) exit
        call h5ldelete_f(gid, drop(k), err)
        if (err < 0) then
          ok = .false.
          errmsg = op_err(w, 'unlink /steps/'//drop(k))
        end if
      end do
      if (ok) call update_attr_int(w, gid, 'count', keep_steps, ok, errmsg)
      call end_group(w, gid, 'steps', ok, errmsg); if (.not. ok) exit restore
      w%n_steps = keep_steps

      call flush_file(w, ok, errmsg); if (.not. ok) exit restore
      if (comms_is_root()) then
        if (w%n_steps > 0) then
          call write_xmf(w, ok, errmsg)
        else
          ! no committed step: no index (as after fw_open)
          call remove_if_present(w%xmf_path)
          call remove_if_present(w%xmf_path//'.tmp')
        end if
      end if
      return
    end block restore

    ok = .false.
    call fw_close(w)
  end subroutine fw_reopen

  !> Open output step number n_steps (group /steps/NNNNNN) and write the
  !> current coordinates x(size(node_gidx),3), this rank's rows.
  subroutine fw_begin_step_ik(w, time, cycle, x, ok, errmsg)
    type(field_writer_t), intent(inout) :: w
    real(rk), intent(in) :: time
    integer(ik), intent(in) :: cycle
    real(rk), intent(in) :: x(:,:)
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    call fw_begin_step_i8(w, time, int(cycle, i8), x, ok, errmsg)
  end subroutine fw_begin_step_ik

  subroutine fw_begin_step_i8(w, time, cycle, x, ok, errmsg)
    type(field_writer_t), intent(inout) :: w
    real(rk), intent(in) :: time
    integer(i8), intent(in) :: cycle
    real(rk), intent(in) :: x(:,:)
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg

    integer :: err
    character(len=step_digits) :: gname

    ok = .false.
    errmsg = ''
    if (.not. w%is_open) then
      errmsg = 'field_output: fw_begin_step on a writer that is not open'
      return
    end if
    if (w%in_step) then
      errmsg = op_err(w, 'fw_begin_step: previous step '//w%cur%group// &
                      ' not ended (missing fw_end_step)')
      return
    end if
    if (size(x, 1) /= w%node_rows%n .or. size(x, 2) /= 3) then
      errmsg = op_err(w, 'fw_begin_step: x must have shape (size(node_gidx),3)')
      return
    end if

    write(gname, '(i6.6)') w%n_steps
    call h5gcreate_f(w%file_id, '/steps/'//gname, w%step_gid, err)
    if (err < 0) then
      errmsg = op_err(w, 'create group /steps/'//gname)
      return
    end if
    w%in_step = .true.
    w%cur%time = time
    w%cur%cycle = cycle
    w%cur%group = gname
    w%cur%n_fields = 0
    w%cur%n_particles = -1
    if (.not. allocated(w%cur%fields)) allocate(w%cur%fields(8))

    call attr_num(w, w%step_gid, 'time', time, ok, errmsg); if (.not. ok) return
    call attr_num(w, w%step_gid, 'cycle', cycle, ok, errmsg); if (.not. ok) return
    call write_vector(w, w%step_gid, 'coordinates', x, ok, errmsg)
    if (ok) call dataset_attrs(w, w%step_gid, 'coordinates', 'm', 'Node', ok, errmsg)
  end subroutine fw_begin_step_i8

  !> Nodal vector field a(size(node_gidx),3), stored C-order (n_nodes,3).
  subroutine fw_node_vector(w, name, a, ok, errmsg, units)
    type(field_writer_t), intent(inout) :: w
    character(len=*), intent(in) :: name
    real(rk), intent(in) :: a(:,:)
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    character(len=*), intent(in), optional :: units
    call write_field(w, name, fk_node_vector, size(a, 1) == w%node_rows%n .and. size(a, 2) == 3, &
                     ok, errmsg, units, vector=a)
  end subroutine fw_node_vector

  !> Nodal scalar field a(size(node_gidx)), stored (n_nodes,).
  subroutine fw_node_scalar(w, name, a, ok, errmsg, units)
    type(field_writer_t), intent(inout) :: w
    character(len=*), intent(in) :: name
    real(rk), intent(in) :: a(:)
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    character(len=*), intent(in), optional :: units
    call write_field(w, name, fk_node_scalar, size(a) == w%node_rows%n, ok, errmsg, units, scalar=a)
  end subroutine fw_node_scalar

  !> Element (cell) scalar field a(size(elem_gidx)), stored (n_elems,).
  subroutine fw_elem_scalar(w, name, a, ok, errmsg, units)
    type(field_writer_t), intent(inout) :: w
    character(len=*), intent(in) :: name
    real(rk), intent(in) :: a(:)
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    character(len=*), intent(in), optional :: units
    call write_field(w, name, fk_elem_scalar, size(a) == w%elem_rows%n, ok, errmsg, units, scalar=a)
  end subroutine fw_elem_scalar

  !> The particles of the step (collective; every rank passes them all, the
  !> root writes them): group /steps/NNNNNN/particles with @count, its
  !> coordinates and velocity (count,3) and the scalars particle_scalars
  !> (count) as values(:, k); listed in <case>_particles.xmf (a point set,
  !> which ParaView shows beside the mesh).
  subroutine fw_particles(w, x, v, values, ok, errmsg)
    type(field_writer_t), intent(inout) :: w
    real(rk), intent(in) :: x(:,:), v(:,:), values(:,:)
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer(hid_t) :: gid
    integer :: k, n
    ok = .false.
    errmsg = ''
    if (.not. w%in_step) then
      errmsg = 'field_output: fw_particles outside a step'
      return
    end if
    n = size(x, 2)
    call make_group(w, w%step_gid, 'particles', gid, ok, errmsg); if (.not. ok) return
    call attr_num(w, gid, 'count', int(n, i8), ok, errmsg)
    if (ok .and. n > 0) then
      call write_whole(gid, 'coordinates', 3, x)
      if (ok) call write_whole(gid, 'velocity', 3, v)
      do k = 1, size(particle_scalars)
        if (.not. ok) exit
        call write_whole(gid, trim(particle_scalars(k)), 0, reshape(values(:,k), [1, n]))
      end do
    end if
    call end_group(w, gid, 'particles', ok, errmsg)
    if (ok) w%cur%n_particles = n
  contains
    !> A dataset of all n rows (width 0: 1-D), written by the root alone.
    subroutine write_whole(loc, name, width, a)
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      integer, intent(in) :: width
      real(rk), intent(in), target :: a(:,:)
      integer(hid_t) :: fsid, msid, did
      integer :: err, e2, rank
      integer(hsize_t) :: dims(2)
      real(rk), target :: dummy(1)
      type(c_ptr) :: p
      rank = merge(1, 2, width == 0)
      dims = [int(max(width, 1), hsize_t), int(n, hsize_t)]
      if (rank == 1) dims(1) = int(n, hsize_t)
      call h5screate_simple_f(rank, dims(1:rank), fsid, err)
      call h5dcreate_f(loc, name, H5T_IEEE_F64LE, fsid, did, err)
      if (err < 0) then
        ok = .false.
        errmsg = op_err(w, 'create dataset particles/'//name)
        call h5sclose_f(fsid, e2)
        return
      end if
      if (comms_is_root()) then
        call h5screate_simple_f(rank, dims(1:rank), msid, err)
        p = c_loc(a)
      else
        call h5sselect_none_f(fsid, err)
        call h5screate_simple_f(1, [1_hsize_t], msid, err)
        call h5sselect_none_f(msid, err)
        p = c_loc(dummy)
      end if
      call h5dwrite_f(did, h5kind_to_type(rk, H5_REAL_KIND), p, err, mem_space_id=msid, file_space_id=fsid, &
                      xfer_prp=w%dxpl)
      err = comms_min_int(err)
      if (err < 0) then
        ok = .false.
        errmsg = op_err(w, 'write dataset particles/'//name)
      end if
      call h5sclose_f(msid, e2)
      call h5sclose_f(fsid, e2)
      call h5dclose_f(did, e2)
    end subroutine
  end subroutine fw_particles

  !> Commit the current step: close its group, bump /steps@count, flush the
  !> file (collective) and, on rank 0, atomically replace the .xmf.
  subroutine fw_end_step(w, ok, errmsg)
    type(field_writer_t), intent(inout) :: w
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg

    integer :: err
    integer(hid_t) :: gid

    ok = .false.
    errmsg = ''
    if (.not. w%is_open .or. .not. w%in_step) then
      errmsg = 'field_output: fw_end_step without a matching fw_begin_step'
      return
    end if

    call h5gclose_f(w%step_gid, err)
    w%step_gid = -1
    w%in_step = .false.
    if (err < 0) then
      errmsg = op_err(w, 'close group /steps/'//w%cur%group)
      return
    end if

    ! Record the step before touching the count so list and file agree.
    call append_step(w)

    call h5gopen_f(w%file_id, 'steps', gid, err)
    if (err < 0) then
      errmsg = op_err(w, 'open group /steps')
      return
    end if
    call update_attr_int(w, gid, 'count', int(w%n_steps, ik), ok, errmsg)
    call end_group(w, gid, 'steps', ok, errmsg); if (.not. ok) return

    ! Flush before publishing the .xmf so it never names unwritten data.
    call flush_file(w, ok, errmsg); if (.not. ok) return

    if (comms_is_root()) call write_xmf(w, ok, errmsg)
    if (ok .and. comms_is_root() .and. any(w%steps(1:w%n_steps)%n_particles >= 0)) call write_particles_xmf(w, ok, errmsg)
  end subroutine fw_end_step

  !> Close the file and reset the writer (collective when open).  Safe on a
  !> writer that is not open.  A step begun but not ended is unlinked: it
  !> was never committed.
  subroutine fw_close(w)
    type(field_writer_t), intent(inout) :: w
    integer :: err

    if (w%is_open) then
      if (w%in_step) then
        call h5gclose_f(w%step_gid, err)
        call h5ldelete_f(w%file_id, '/steps/'//w%cur%group, err)
      end if
      call h5fclose_f(w%file_id, err)
    end if
    if (w%dxpl /= -1) call h5pclose_f(w%dxpl, err)
    w%dxpl = -1
    w%is_open = .false.
    w%in_step = .false.
    w%file_id = -1
    w%step_gid = -1
    w%n_nodes = 0
    w%n_elems = 0
    call free_rows(w%node_rows)
    call free_rows(w%elem_rows)
    w%n_steps = 0
    if (allocated(w%steps)) deallocate(w%steps)
    if (allocated(w%cur%fields)) deallocate(w%cur%fields)
    w%cur%n_fields = 0
    if (allocated(w%buf)) deallocate(w%buf)
    if (allocated(w%h5_path)) deallocate(w%h5_path)
    if (allocated(w%xmf_path)) deallocate(w%xmf_path)
    if (allocated(w%h5_ref)) deallocate(w%h5_ref)
    if (allocated(w%title)) deallocate(w%title)
  end subroutine fw_close

  ! ---------------------------------------------------------- open helpers

  !> Argument problems that are the same on every rank (so every rank
  !> returns before the first collective call).  '' if none.
  function common_arg_error(w, who, h5_path, xmf_path, n_nodes_global, n_elems_global) result(msg)
    type(field_writer_t), intent(in) :: w
    character(len=*), intent(in) :: who, h5_path, xmf_path
    integer(ik), intent(in) :: n_nodes_global, n_elems_global
    character(len=:), allocatable :: msg

    msg = ''
    if (w%is_open) then
      msg = 'field_output: '//who//' called on a writer that is already open ('//w%h5_path//')'
    else if (n_nodes_global < 1 .or. n_elems_global < 1) then
      msg = 'field_output: '//who//' needs at least one node and one element'
    else if (len_trim(h5_path) == 0 .or. len_trim(xmf_path) == 0) then
      msg = 'field_output: empty output path'
    else if (trim(h5_path) == trim(xmf_path)) then
      msg = 'field_output: h5 and xmf paths are the same: '//trim(h5_path)
    else if (dir_name(trim(h5_path)) /= dir_name(trim(xmf_path))) then
      ! The .xmf refers to the h5 by base name, so both must share a directory.
      msg = 'field_output: "'//trim(h5_path)//'" and "'//trim(xmf_path)// &
            '" must be in the same directory (the .xmf references the h5 by base name)'
    end if
  end function common_arg_error

  !> The runs of consecutive indices in gidx (1-based global indices,
  !> strictly ascending, within 1..n_global).  errmsg set if gidx is not so.
  subroutine make_rows(gidx, n_global, what, rows, errmsg)
    integer(ik), intent(in) :: gidx(:), n_global
    character(len=*), intent(in) :: what
    type(rows_t), intent(out) :: rows
    character(len=:), allocatable, intent(inout) :: errmsg
    integer :: k, n, r

    n = size(gidx)
    if (n > 0) then
      do k = 2, n
        if (gidx(k) <= gidx(k-1)) then
          errmsg = 'field_output: '//what//' is not strictly ascending (entry '//itoa(k)//')'
          return
        end if
      end do
      if (gidx(1) < 1 .or. gidx(n) > n_global) then
        errmsg = 'field_output: '//what//' holds indices outside 1..'//itoa(n_global)
        return
      end if
    end if
    rows%n = n
    rows%n_global = int(n_global, hsize_t)
    rows%n_runs = 0
    do k = 1, n
      if (k == 1) then
        rows%n_runs = 1
      else if (gidx(k) /= gidx(k-1) + 1) then
        rows%n_runs = rows%n_runs + 1
      end if
    end do
    allocate(rows%first(rows%n_runs), rows%count(rows%n_runs))
    r = 0
    do k = 1, n
      if (k == 1) then
        r = 1
      else if (gidx(k) /= gidx(k-1) + 1) then
        r = r + 1
      else
        rows%count(r) = rows%count(r) + 1
        cycle
      end if
      rows%first(r) = int(gidx(k) - 1, hsize_t)
      rows%count(r) = 1
    end do
  end subroutine make_rows

  subroutine init_writer(w, h5_path, xmf_path, title, n_nodes_global, n_elems_global, nrows, erows)
    type(field_writer_t), intent(inout) :: w
    character(len=*), intent(in) :: h5_path, xmf_path, title
    integer(ik), intent(in) :: n_nodes_global, n_elems_global
    type(rows_t), intent(in) :: nrows, erows

    w%h5_path = trim(h5_path)
    w%xmf_path = trim(xmf_path)
    w%h5_ref = base_name(w%h5_path)
    w%title = title
    w%n_nodes = n_nodes_global
    w%n_elems = n_elems_global
    w%node_rows = nrows
    w%elem_rows = erows
    w%n_steps = 0
    if (allocated(w%buf)) deallocate(w%buf)
    allocate(w%buf(3, nrows%n))
  end subroutine init_writer

  !> Create (create=.true., truncating) or open read-write the file with
  !> the MPI-IO driver on the world communicator, and make the collective
  !> transfer property list.  Collective; ok is the same on every rank.
  subroutine open_file(w, create, ok, errmsg)
    type(field_writer_t), intent(inout) :: w
    logical, intent(in) :: create
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer(hid_t) :: fapl
    integer :: err, e2

    ok = .false.
    errmsg = ''
    ! Fortran HDF5 constants are only valid after h5open_f; calling it again
    ! is harmless and protects against another module having called h5close_f.
    call h5open_f(err)
    if (err < 0) then
      errmsg = 'field_output: HDF5 library initialisation (h5open_f) failed'
      return
    end if
    ! Errors are reported through errmsg only.
    call h5eset_auto_f(0, err)

    ! MPI-IO on the world communicator (HDF5 duplicates it).
    call h5pcreate_f(H5P_FILE_ACCESS_F, fapl, err)
    if (err < 0) then
      errmsg = op_err(w, 'create file access property list (h5pcreate_f)')
      return
    end if
    call h5pset_fapl_mpio_f(fapl, comms_world_handle(), comms_info_null_handle(), err)
    if (err < 0) then
      call h5pclose_f(fapl, e2)
      errmsg = op_err(w, 'set up MPI-IO file access (h5pset_fapl_mpio_f)')
      return
    end if
    if (create) then
      call h5fcreate_f(w%h5_path, H5F_ACC_TRUNC_F, w%file_id, err, access_prp=fapl)
    else
      call h5fopen_f(w%h5_path, H5F_ACC_RDWR_F, w%file_id, err, access_prp=fapl)
    end if
    call h5pclose_f(fapl, e2)
    if (err < 0) then
      if (create) then
        errmsg = op_err(w, 'create file (h5fcreate_f)')
      else
        errmsg = op_err(w, 'open existing file read-write (h5fopen_f)')
      end if
      w%file_id = -1
      return
    end if
    w%is_open = .true.

    call h5pcreate_f(H5P_DATASET_XFER_F, w%dxpl, err)
    if (err >= 0) call h5pset_dxpl_mpio_f(w%dxpl, H5FD_MPIO_COLLECTIVE_F, err)
    if (err < 0) then
      errmsg = op_err(w, 'set up collective transfers (h5pset_dxpl_mpio_f)')
      call fw_close(w)
      return
    end if
    ok = .true.
  end subroutine open_file

  !> Collective flush of the whole file.
  subroutine flush_file(w, ok, errmsg)
    type(field_writer_t), intent(in) :: w
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer :: err

    errmsg = ''
    call h5fflush_f(w%file_id, H5F_SCOPE_GLOBAL_F, err)
    ok = comms_min_int(err) >= 0
    if (.not. ok) errmsg = op_err(w, 'flush (h5fflush_f)')
  end subroutine flush_file

  !> Append the step being written (w%cur) to the committed ones.
  subroutine append_step(w)
    type(field_writer_t), intent(inout) :: w
    type(step_rec_t), allocatable :: tmp(:)

    if (.not. allocated(w%steps)) allocate(w%steps(16))
    if (w%n_steps >= size(w%steps)) then
      allocate(tmp(2*size(w%steps)))
      tmp(1:w%n_steps) = w%steps(1:w%n_steps)
      call move_alloc(tmp, w%steps)
    end if
    w%n_steps = w%n_steps + 1
    w%steps(w%n_steps) = w%cur
    w%steps(w%n_steps)%fields = w%cur%fields(1:w%cur%n_fields)
  end subroutine append_step

  ! -------------------------------------------------------- reopen helpers

  !> The record of committed step number k (0-based) of the open file:
  !> time, cycle and its fields with their kinds, in link-name order.
  subroutine read_step_rec(w, k, st, ok, errmsg)
    type(field_writer_t), intent(in) :: w
    integer, intent(in) :: k
    type(step_rec_t), intent(out) :: st
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg

    character(len=:), allocatable :: gpath, name
    character(len=256) :: lname
    integer(size_t) :: lsize
    real(rk), target :: t
    integer(i8), target :: cyc
    integer(hid_t) :: gid
    integer :: err, storage, n_links, max_corder, i, kind
    logical :: has_coords

    ok = .false.
    write(st%group, '(i6.6)') k
    gpath = 'steps/'//st%group
    call read_attr(w, w%file_id, gpath, 'time', h5kind_to_type(rk, H5_REAL_KIND), c_loc(t), &
                   ok, errmsg); if (.not. ok) return
    call read_attr(w, w%file_id, gpath, 'cycle', h5kind_to_type(i8, H5_INTEGER_KIND), c_loc(cyc), &
                   ok, errmsg); if (.not. ok) return
    st%time = t
    st%cycle = cyc
    ok = .false.

    call h5gopen_f(w%file_id, gpath, gid, err)
    if (err < 0) then
      errmsg = op_err(w, 'open group /'//gpath)
      return
    end if
    call h5gget_info_f(gid, storage, n_links, max_corder, err)
    if (err < 0) then
      errmsg = op_err(w, 'list group /'//gpath)
      call h5gclose_f(gid, err)
      return
    end if
    allocate(st%fields(max(1, n_links)))
    st%n_fields = 0
    has_coords = .false.
    do i = 0, n_links - 1
      lname = ''
      call h5lget_name_by_idx_f(gid, '.', H5_INDEX_NAME_F, H5_ITER_INC_F, int(i, hsize_t), &
                                lname, err, lsize)
      if (err < 0 .or. lsize > len(lname)) then
        errmsg = op_err(w, 'read link names of /'//gpath)
        exit
      end if
      name = trim(lname)
      if (name == 'coordinates') then
        has_coords = .true.
        cycle
      end if
      if (name == 'particles') then
        call read_attr(w, w%file_id, gpath//'/particles', 'count', h5kind_to_type(i8, H5_INTEGER_KIND), c_loc(cyc), &
                       ok, errmsg)
        if (.not. ok) exit
        st%n_particles = int(cyc)
        cycle
      end if
      call field_kind(w, gid, gpath, name, kind, errmsg)
      if (kind == 0) exit
      st%n_fields = st%n_fields + 1
      st%fields(st%n_fields)%name = name
      st%fields(st%n_fields)%kind = kind
    end do
    call h5gclose_f(gid, err)
    if (len(errmsg) > 0) return
    if (.not. has_coords) then
      errmsg = 'field_output: cannot reopen "'//w%h5_path//'": step /'//gpath//' has no coordinates'
      return
    end if
    ok = .true.
  end subroutine read_step_rec

  !> Field kind of dataset name in step group gid from its shape: (n_nodes,3)
  !> node vector, (n_nodes,) node scalar, (n_elems,) element scalar.  When
  !> n_nodes == n_elems a 1-D field is ambiguous; the Center in the existing
  !> .xmf decides (node scalar if it does not say).  kind 0 and errmsg set on
  !> a dataset of any other shape.
  subroutine field_kind(w, gid, gpath, name, kind, errmsg)
    type(field_writer_t), intent(in) :: w
    integer(hid_t), intent(in) :: gid
    character(len=*), intent(in) :: gpath, name
    integer, intent(out) :: kind
    character(len=:), allocatable, intent(inout) :: errmsg
    integer(hid_t) :: did, sid
    integer(hsize_t) :: dims(2), maxdims(2)
    integer :: err, e2, rank
    integer(hsize_t) :: nn, ne

    kind = 0
    nn = int(w%n_nodes, hsize_t)
    ne = int(w%n_elems, hsize_t)
    call h5dopen_f(gid, name, did, err)
    if (err < 0) then
      errmsg = op_err(w, 'open dataset /'//gpath//'/'//name)
      return
    end if
    call h5dget_space_f(did, sid, err)
    if (err >= 0) then
      call h5sget_simple_extent_ndims_f(sid, rank, err)
      if (err >= 0 .and. rank >= 1 .and. rank <= 2) &
        call h5sget_simple_extent_dims_f(sid, dims(1:rank), maxdims(1:rank), err)
      call h5sclose_f(sid, e2)
    end if
    call h5dclose_f(did, e2)
    if (err < 0) then
      errmsg = op_err(w, 'read the shape of /'//gpath//'/'//name)
      return
    end if
    ! Fortran order: C (n_nodes,3) is (3,n_nodes) here
    if (rank == 2) then
      if (dims(1) == 3 .and. dims(2) == nn) kind = fk_node_vector
    else if (rank == 1) then
      if (dims(1) == nn .and. dims(1) == ne) then
        kind = fk_node_scalar
        if (xmf_center(w%xmf_path, gpath(len(gpath)-step_digits+1:), name) == 'Cell') &
          kind = fk_elem_scalar
      else if (dims(1) == nn) then
        kind = fk_node_scalar
      else if (dims(1) == ne) then
        kind = fk_elem_scalar
      end if
    end if
    if (kind == 0) errmsg = 'field_output: cannot reopen "'//w%h5_path//'": dataset /'// &
      gpath//'/'//name//' has the shape of no field of this mesh'
  end subroutine field_kind

  !> Center ('Node' or 'Cell') given to field name of step group in an
  !> existing .xmf written by this module; '' if the file or entry is absent.
  function xmf_center(path, group, name) result(center)
    character(len=*), intent(in) :: path, group, name
    character(len=:), allocatable :: center
    character(len=4096) :: line
    integer :: u, ios
    logical :: in_step

    center = ''
    open(newunit=u, file=path, status='old', action='read', iostat=ios)
    if (ios /= 0) return
    in_step = .false.
    do
      read(u, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (index(line, '<Grid Name="step_'//group//'"') > 0) then
        in_step = .true.
      else if (in_step .and. index(line, '</Grid>') > 0) then
        exit
      else if (in_step .and. index(line, '<Attribute Name="'//name//'"') > 0) then
        if (index(line, 'Center="Cell"') > 0) center = 'Cell'
        if (index(line, 'Center="Node"') > 0) center = 'Node'
        exit
      end if
    end do
    close(u)
  end function xmf_center

  !> Names of the step groups in /steps (gid) numbered keep or above,
  !> committed or not.  Other links are not ours and are left alone.
  subroutine list_step_groups(w, gid, keep, names, n, ok, errmsg)
    type(field_writer_t), intent(in) :: w
    integer(hid_t), intent(in) :: gid
    integer(ik), intent(in) :: keep
    character(len=step_digits), allocatable, intent(out) :: names(:)
    integer, intent(out) :: n
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    character(len=256) :: lname
    integer(size_t) :: lsize
    integer :: err, storage, n_links, max_corder, i, num, ios

    ok = .false.
    errmsg = ''
    n = 0
    call h5gget_info_f(gid, storage, n_links, max_corder, err)
    if (err < 0) then
      errmsg = op_err(w, 'list group /steps')
      return
    end if
    allocate(names(n_links))
    do i = 0, n_links - 1
      lname = ''
      call h5lget_name_by_idx_f(gid, '.', H5_INDEX_NAME_F, H5_ITER_INC_F, int(i, hsize_t), &
                                lname, err, lsize)
      if (err < 0) then
        errmsg = op_err(w, 'read link names of /steps')
        return
      end if
      if (lsize /= step_digits) cycle
      if (verify(lname(1:step_digits), '0123456789') /= 0) cycle
      read(lname(1:step_digits), '(i6)', iostat=ios) num
      if (ios /= 0) cycle
      if (num < keep) cycle
      n = n + 1
      names(n) = lname(1:step_digits)
    end do
    ok = .true.
  end subroutine list_step_groups

  ! ---------------------------------------------------------- step helpers

  !> Common checks for a field write: open step, valid and unused name.
  subroutine check_field(w, name, ok, errmsg)
    type(field_writer_t), intent(in) :: w
    character(len=*), intent(in) :: name
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer :: i

    ok = .false.
    errmsg = ''
    if (.not. w%is_open .or. .not. w%in_step) then
      errmsg = 'field_output: field "'//trim(name)//'" written outside fw_begin_step/fw_end_step'
      return
    end if
    if (.not. valid_name(trim(name))) then
      errmsg = op_err(w, 'invalid field name "'//trim(name)// &
               '" (use [A-Za-z_][A-Za-z0-9_.-]*, at most 64 chars, not coordinates/part_id)')
      return
    end if
    do i = 1, w%cur%n_fields
      if (w%cur%fields(i)%name == trim(name)) then
        errmsg = op_err(w, 'field "'//trim(name)//'" written twice in step '//w%cur%group)
        return
      end if
    end do
    ok = .true.
  end subroutine check_field

  !> What the three field writers share: checks of the step, name and shape
  !> (fits: the array has the local shape of its kind), the dataset with its
  !> units (when given) and centering ('Node' or 'Cell') as attributes, the
  !> record.
  subroutine write_field(w, name, kind, fits, ok, errmsg, units, vector, scalar)
    type(field_writer_t), intent(inout) :: w
    character(len=*), intent(in) :: name
    integer, intent(in) :: kind
    logical, intent(in) :: fits
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    character(len=*), intent(in), optional :: units
    real(rk), intent(in), optional :: vector(:,:), scalar(:)

    call check_field(w, name, ok, errmsg); if (.not. ok) return
    if (.not. fits) then
      ok = .false.
      select case (kind)
      case (fk_node_vector)
        errmsg = op_err(w, 'fw_node_vector "'//trim(name)//'": shape must be (size(node_gidx),3)')
      case (fk_node_scalar)
        errmsg = op_err(w, 'fw_node_scalar "'//trim(name)//'": size must be size(node_gidx)')
      case default
        errmsg = op_err(w, 'fw_elem_scalar "'//trim(name)//'": size must be size(elem_gidx)')
      end select
      return
    end if
    if (present(vector)) then
      call write_vector(w, w%step_gid, trim(name), vector, ok, errmsg)
    else if (kind == fk_node_scalar) then
      call write_data(w, w%step_gid, trim(name), on_nodes, 0, ok, errmsg, reals=scalar)
    else
      call write_data(w, w%step_gid, trim(name), on_elems, 0, ok, errmsg, reals=scalar)
    end if
    if (ok) then
      if (kind == fk_elem_scalar) then
        call dataset_attrs(w, w%step_gid, trim(name), units, 'Cell', ok, errmsg)
      else
        call dataset_attrs(w, w%step_gid, trim(name), units, 'Node', ok, errmsg)
      end if
    end if
    if (ok) call add_field(w, trim(name), kind)
  end subroutine write_field

  !> The string attributes 'units' (when given) and 'center' of dataset
  !> name in loc (collective: every rank passes the same values).
  subroutine dataset_attrs(w, loc, name, units, center, ok, errmsg)
    type(field_writer_t), intent(in) :: w
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name, center
    character(len=*), intent(in), optional :: units
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer(hid_t) :: did
    integer :: err, e2
    ok = .false.
    call h5dopen_f(loc, name, did, err)
    if (err < 0) then
      errmsg = op_err(w, 'open dataset '//name//' for its attributes')
      return
    end if
    ok = .true.
    if (present(units)) call attr_str(w, did, 'units', units, ok, errmsg)
    if (ok) call attr_str(w, did, 'center', center, ok, errmsg)
    call h5dclose_f(did, e2)
    if (ok .and. e2 < 0) then
      ok = .false.
      errmsg = op_err(w, 'close dataset '//name)
    end if
  end subroutine dataset_attrs

  !> Names become HDF5 link names and XML attribute values: keep them plain.
  pure logical function valid_name(name)
    character(len=*), intent(in) :: name
    integer :: i
    character :: c

    valid_name = .false.
    if (len(name) < 1 .or. len(name) > max_name_len) return
    if (name == 'coordinates' .or. name == 'part_id') return
    do i = 1, len(name)
      c = name(i:i)
      if (is_letter(c) .or. c == '_') cycle
      if (i > 1 .and. (is_digit(c) .or. c == '.' .or. c == '-')) cycle
      return
    end do
    valid_name = .true.
  end function valid_name

  subroutine add_field(w, name, kind)
    type(field_writer_t), intent(inout) :: w
    character(len=*), intent(in) :: name
    integer, intent(in) :: kind
    type(field_rec_t), allocatable :: tmp(:)

    if (w%cur%n_fields >= size(w%cur%fields)) then
      allocate(tmp(2*size(w%cur%fields)))
      tmp(1:w%cur%n_fields) = w%cur%fields(1:w%cur%n_fields)
      call move_alloc(tmp, w%cur%fields)
    end if
    w%cur%n_fields = w%cur%n_fields + 1
    w%cur%fields(w%cur%n_fields)%name = name
    w%cur%fields(w%cur%n_fields)%kind = kind
  end subroutine add_field

  !> Transpose a(n,3) into the (3,n) buffer: Fortran (3,n) is C-order (n,3).
  subroutine write_vector(w, loc, name, a, ok, errmsg)
    type(field_writer_t), intent(inout) :: w
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    real(rk), intent(in) :: a(:,:)
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer :: i, j

    do j = 1, 3
      do i = 1, size(a, 1)
        w%buf(j, i) = a(i, j)
      end do
    end do
    call write_data(w, loc, name, on_nodes, 3, ok, errmsg, reals=w%buf)
  end subroutine write_vector

  ! ----------------------------------------------------------- XDMF output

  !> Rewrite the whole .xmf (small: one Grid per step) to <xmf>.tmp, then
  !> rename over the old one so a concurrent reader never sees a partial file.
  subroutine write_xmf(w, ok, errmsg)
    type(field_writer_t), intent(in) :: w
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg

    character(len=:), allocatable :: tmp_path, h5
    character(len=512) :: iomsg
    character(len=32) :: sn, se, st
    integer :: u, ios, s, f

    ok = .false.
    errmsg = ''
    tmp_path = w%xmf_path//'.tmp'
    h5 = xml_escape(w%h5_ref)
    write(sn, '(i0)') w%n_nodes
    write(se, '(i0)') w%n_elems

    call xmf_begin(tmp_path, w%title, u, ios, iomsg, errmsg)
    if (len(errmsg) > 0) return

    do s = 1, w%n_steps
      if (ios /= 0) exit
      associate (st_rec => w%steps(s))
        write(st, '(es24.16e3)') st_rec%time
        write(u, '(a)', iostat=ios, iomsg=iomsg) &
          '      <Grid Name="step_'//st_rec%group//'" GridType="Uniform">'
        if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) &
          '        <Time Value="'//trim(adjustl(st))//'"/>'
        if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) &
          '        <Topology TopologyType="'//trim(merge('Tetrahedron', 'Triangle   ', w%corners == 4))// &
          '" NumberOfElements="'//trim(se)//'" NodesPerElement="'//itoa(w%corners)//'">'
        if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) &
          '          <DataItem Dimensions="'//trim(se)//' '//itoa(w%corners)// &
          '" NumberType="Int" Precision="4" Format="HDF">'// &
          h5//':/mesh/connectivity</DataItem>'
        if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) '        </Topology>'
        if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) '        <Geometry GeometryType="XYZ">'
        if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) &
          '          <DataItem Dimensions="'//trim(sn)//' 3" NumberType="Float" Precision="8" Format="HDF">'// &
          h5//':/steps/'//st_rec%group//'/coordinates</DataItem>'
        if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) '        </Geometry>'
        if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) &
          '        <Attribute Name="part_id" AttributeType="Scalar" Center="Cell">'
        if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) &
          '          <DataItem Dimensions="'//trim(se)//'" NumberType="Int" Precision="4" Format="HDF">'// &
          h5//':/mesh/part_id</DataItem>'
        if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) '        </Attribute>'
        do f = 1, st_rec%n_fields
          if (ios /= 0) exit
          call write_xmf_field(u, h5, st_rec%group, st_rec%fields(f), sn, se, ios, iomsg)
        end do
        if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) '      </Grid>'
      end associate
    end do

    call xmf_end(u, tmp_path, w%xmf_path, ios, iomsg, ok, errmsg)
  end subroutine write_xmf

  !> Opens tmp_path and writes an XDMF index's head, up to the temporal
  !> collection named title (errmsg set when it cannot be opened).
  subroutine xmf_begin(tmp_path, title, u, ios, iomsg, errmsg)
    character(len=*), intent(in) :: tmp_path, title
    integer, intent(out) :: u, ios
    character(len=*), intent(inout) :: iomsg
    character(len=:), allocatable, intent(out) :: errmsg
    errmsg = ''
    open(newunit=u, file=tmp_path, status='replace', action='write', &
         form='formatted', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      errmsg = 'field_output: cannot open "'//tmp_path//'" for writing: '//trim(iomsg)
      return
    end if
    write(u, '(a)', iostat=ios, iomsg=iomsg) '<?xml version="1.0" ?>'
    if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) &
      '<Xdmf Version="3.0" xmlns:xi="http://www.w3.org/2001/XInclude">'
    if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) '  <Domain>'
    if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) &
      '    <Grid Name="'//xml_escape(title)//'" GridType="Collection" CollectionType="Temporal">'
  end subroutine xmf_begin

  !> Closes an index xmf_begin opened (ios: how its writes went) and renames
  !> it over path, so a reader never sees a partial file.
  subroutine xmf_end(u, tmp_path, path, ios, iomsg, ok, errmsg)
    integer, intent(in) :: u
    character(len=*), intent(in) :: tmp_path, path
    integer, intent(inout) :: ios
    character(len=*), intent(inout) :: iomsg
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    ok = .false.
    errmsg = ''
    if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) '    </Grid>'
    if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) '  </Domain>'
    if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) '</Xdmf>'
    if (ios /= 0) then
      errmsg = 'field_output: write to "'//tmp_path//'" failed: '//trim(iomsg)
      close(u, status='delete', iostat=ios)
      return
    end if
    close(u, iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      errmsg = 'field_output: close of "'//tmp_path//'" failed: '//trim(iomsg)
      return
    end if
    if (.not. rename_file(tmp_path, path)) then
      errmsg = 'field_output: rename "'//tmp_path//'" -> "'//path//'" failed'
      return
    end if
    ok = .true.
  end subroutine xmf_end

  !> The particles' index, <case>_particles.xmf beside <case>.xmf (written
  !> as write_xmf writes that one): a temporal collection of point sets
  !> (Polyvertex), one per step that has particles.
  subroutine write_particles_xmf(w, ok, errmsg)
    type(field_writer_t), intent(in) :: w
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    character(len=:), allocatable :: path, tmp_path, h5, gp
    character(len=512) :: iomsg
    character(len=32) :: st, sn
    integer :: u, ios, s, k
    ok = .false.
    errmsg = ''
    path = w%xmf_path(1:len(w%xmf_path)-4)//'_particles.xmf'
    tmp_path = path//'.tmp'
    h5 = xml_escape(w%h5_ref)
    call xmf_begin(tmp_path, w%title//' particles', u, ios, iomsg, errmsg)
    if (len(errmsg) > 0) return
    do s = 1, w%n_steps
      if (ios /= 0) exit
      associate (rec => w%steps(s))
        if (rec%n_particles <= 0) cycle
        write(st, '(es24.16e3)') rec%time
        write(sn, '(i0)') rec%n_particles
        gp = h5//':/steps/'//rec%group//'/particles/'
        write(u, '(a)', iostat=ios, iomsg=iomsg) '      <Grid Name="particles_'//rec%group//'" GridType="Uniform">'
        if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) '        <Time Value="'//trim(adjustl(st))//'"/>'
        if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) &
          '        <Topology TopologyType="Polyvertex" NumberOfElements="'//trim(sn)//'" NodesPerElement="1"/>'
        if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) '        <Geometry GeometryType="XYZ">'
        if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) &
          '          <DataItem Dimensions="'//trim(sn)//' 3" NumberType="Float" Precision="8" Format="HDF">'// &
          gp//'coordinates</DataItem>'
        if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) '        </Geometry>'
        ! the particles are the grid's points: their fields are node fields of count rows
        if (ios == 0) call write_xmf_field(u, h5, rec%group//'/particles', field_rec_t('velocity', fk_node_vector), &
                                           sn, sn, ios, iomsg)
        do k = 1, size(particle_scalars)
          if (ios /= 0) exit
          call write_xmf_field(u, h5, rec%group//'/particles', field_rec_t(particle_scalars(k), fk_node_scalar), &
                               sn, sn, ios, iomsg)
        end do
        if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) '      </Grid>'
      end associate
    end do
    call xmf_end(u, tmp_path, path, ios, iomsg, ok, errmsg)
  end subroutine write_particles_xmf

  subroutine write_xmf_field(u, h5, group, fld, sn, se, ios, iomsg)
    integer, intent(in) :: u
    character(len=*), intent(in) :: h5, group, sn, se
    type(field_rec_t), intent(in) :: fld
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: iomsg
    character(len=:), allocatable :: atype, center, dims

    select case (fld%kind)
    case (fk_node_vector)
      atype = 'Vector'; center = 'Node'; dims = trim(sn)//' 3'
    case (fk_node_scalar)
      atype = 'Scalar'; center = 'Node'; dims = trim(sn)
    case default
      atype = 'Scalar'; center = 'Cell'; dims = trim(se)
    end select
    write(u, '(a)', iostat=ios, iomsg=iomsg) &
      '        <Attribute Name="'//trim(fld%name)//'" AttributeType="'//atype// &
      '" Center="'//center//'">'
    if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) &
      '          <DataItem Dimensions="'//dims//'" NumberType="Float" Precision="8" Format="HDF">'// &
      h5//':/steps/'//group//'/'//trim(fld%name)//'</DataItem>'
    if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) '        </Attribute>'
  end subroutine write_xmf_field

  pure function xml_escape(s) result(r)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: r
    integer :: i

    r = ''
    do i = 1, len(s)
      select case (s(i:i))
      case ('&'); r = r//'&amp;'
      case ('<'); r = r//'&lt;'
      case ('>'); r = r//'&gt;'
      case ('"'); r = r//'&quot;'
      case ("'"); r = r//'&apos;'
      case default
        ! Control characters (newlines in a title) are not valid in XML
        ! attribute values as-is; a space is good enough for a label.
        if (iachar(s(i:i)) < 32) then
          r = r//' '
        else
          r = r//s(i:i)
        end if
      end select
    end do
  end function xml_escape

  ! ----------------------------------------------------------- HDF5 helpers

  function op_err(w, op) result(msg)
    type(field_writer_t), intent(in) :: w
    character(len=*), intent(in) :: op
    character(len=:), allocatable :: msg
    if (allocated(w%h5_path)) then
      msg = 'field_output: '//op//' failed for "'//w%h5_path//'"'
    else
      msg = 'field_output: '//op//' failed'
    end if
  end function op_err

  subroutine make_group(w, loc, name, gid, ok, errmsg)
    type(field_writer_t), intent(in) :: w
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer(hid_t), intent(out) :: gid
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer :: err

    errmsg = ''
    call h5gcreate_f(loc, name, gid, err)
    ok = err >= 0
    if (.not. ok) errmsg = op_err(w, 'create group /'//name)
  end subroutine make_group

  !> Close a group after a sequence of writes.  If the writes already
  !> failed (ok false on entry) that first error is kept and the close is
  !> best effort; otherwise a close failure is reported.
  subroutine end_group(w, gid, name, ok, errmsg)
    type(field_writer_t), intent(in) :: w
    integer(hid_t), intent(in) :: gid
    character(len=*), intent(in) :: name
    logical, intent(inout) :: ok
    character(len=:), allocatable, intent(inout) :: errmsg
    integer :: err

    call h5gclose_f(gid, err)
    if (ok .and. err < 0) then
      ok = .false.
      errmsg = op_err(w, 'close group /'//name)
    end if
  end subroutine end_group

  !> Create the global dataset name (collective) and write this rank's rows
  !> (which: on_nodes or on_elems) into it with one collective transfer.
  !> width 0: a 1-D dataset of n_global values; width m: Fortran dims
  !> (m, n_global), which is C-order (n_global, m).  buf holds the local
  !> rows in gidx order (Fortran (m, local rows)); HDF5 maps the selected
  !> elements in file order, which is gidx order.
  subroutine write_rows(w, loc, name, ftype, mtype, which, width, buf, ok, errmsg)
    type(field_writer_t), intent(inout) :: w
    integer(hid_t), intent(in) :: loc, ftype, mtype
    character(len=*), intent(in) :: name
    integer, intent(in) :: which, width
    type(c_ptr), intent(in) :: buf
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg

    integer(hid_t) :: fsid, msid, did
    integer :: err, e2

    ok = .false.
    errmsg = ''
    if (which == on_nodes) then
      call row_spaces(w%node_rows, width, fsid, msid, err)
    else
      call row_spaces(w%elem_rows, width, fsid, msid, err)
    end if
    if (err < 0) then
      errmsg = op_err(w, 'select the rows of dataset '//name)
      return
    end if
    ! only the extent of fsid matters here, its selection is for the write
    call h5dcreate_f(loc, name, ftype, fsid, did, err)
    if (err < 0) then
      errmsg = op_err(w, 'create dataset '//name)
      return
    end if
    call h5dwrite_f(did, mtype, buf, err, mem_space_id=msid, file_space_id=fsid, xfer_prp=w%dxpl)
    ! each rank writes its own rows: on a full disk some fail and others
    ! not, and all must take the same way out of the next collective calls
    err = comms_min_int(err)
    if (err < 0) errmsg = op_err(w, 'write dataset '//name)
    ! after a failed write the first error is kept and the close is best effort
    call h5dclose_f(did, e2)
    if (len(errmsg) > 0) return
    ok = e2 >= 0
    if (.not. ok) errmsg = op_err(w, 'close dataset '//name)
  end subroutine write_rows

  !> The file and memory dataspaces for datasets of these rows and width,
  !> built on first use.  File: the global extent with this rank's rows
  !> selected (the union of its runs).  Memory: the local rows.  A rank
  !> without rows selects nothing in the file (it still takes part in the
  !> collective write) and uses a one-element memory space that selects
  !> nothing (a zero-size dataspace is not allowed).
  subroutine row_spaces(rows, width, fsid, msid, err)
    type(rows_t), intent(inout) :: rows
    integer, intent(in) :: width
    integer(hid_t), intent(out) :: fsid, msid
    integer, intent(out) :: err
    integer(hsize_t) :: dims(2)
    integer(hid_t) :: base
    integer :: rank, e2

    err = 0
    if (rows%fspace(width) == -1) then
      if (width == 0) then
        rank = 1
        dims(1) = rows%n_global
      else
        rank = 2
        dims = [int(width, hsize_t), rows%n_global]
      end if
      call h5screate_simple_f(rank, dims(1:rank), base, err)
      if (err < 0) return
      if (rows%n == 0) then
        call h5sselect_none_f(base, err)
        fsid = base
      else
        fsid = select_runs(base, rows, width, 1, rows%n_runs)
        call h5sclose_f(base, e2)
        if (fsid < 0) err = -1
      end if
      if (err < 0) return
      rows%fspace(width) = fsid

      if (rows%n == 0) then
        call h5screate_simple_f(1, [1_hsize_t], msid, err)
        if (err >= 0) call h5sselect_none_f(msid, err)
      else
        dims(rank) = int(rows%n, hsize_t)
        call h5screate_simple_f(rank, dims(1:rank), msid, err)
      end if
      if (err < 0) return
      rows%mspace(width) = msid
    end if
    fsid = rows%fspace(width)
    msid = rows%mspace(width)
  end subroutine row_spaces

  !> A copy of base (an extent) with runs lo..hi selected.  Adding the runs
  !> one by one with H5S_SELECT_OR costs time quadratic in their number in
  !> HDF5 1.10 (16000 runs: 10 s); halves merged with H5Scombine_select
  !> cost n log n (16000 runs: 0.03 s).  Negative on failure.
  recursive function select_runs(base, rows, width, lo, hi) result(sid)
    integer(hid_t), intent(in) :: base
    type(rows_t), intent(in) :: rows
    integer, intent(in) :: width, lo, hi
    integer(hid_t) :: sid, s1, s2
    integer(hsize_t) :: start(2), cnt(2)
    integer :: r, err, e2, mid

    sid = -1
    if (hi - lo < 16) then
      call h5scopy_f(base, sid, err)
      if (err < 0) then
        sid = -1
        return
      end if
      do r = lo, hi
        if (width == 0) then
          start(1) = rows%first(r)
          cnt(1) = rows%count(r)
          if (r == lo) then
            call h5sselect_hyperslab_f(sid, H5S_SELECT_SET_F, start(1:1), cnt(1:1), err)
          else
            call h5sselect_hyperslab_f(sid, H5S_SELECT_OR_F, start(1:1), cnt(1:1), err)
          end if
        else
          start = [0_hsize_t, rows%first(r)]
          cnt = [int(width, hsize_t), rows%count(r)]
          if (r == lo) then
            call h5sselect_hyperslab_f(sid, H5S_SELECT_SET_F, start, cnt, err)
          else
            call h5sselect_hyperslab_f(sid, H5S_SELECT_OR_F, start, cnt, err)
          end if
        end if
        if (err < 0) then
          call h5sclose_f(sid, e2)
          sid = -1
          return
        end if
      end do
      return
    end if
    mid = (lo + hi)/2
    s1 = select_runs(base, rows, width, lo, mid)
    if (s1 < 0) return
    s2 = select_runs(base, rows, width, mid + 1, hi)
    if (s2 >= 0) sid = int(h5scombine_select_c(int(s1, c_int64_t), int(H5S_SELECT_OR_F, c_int), &
                                                int(s2, c_int64_t)), hid_t)
    call h5sclose_f(s1, e2)
    if (s2 >= 0) call h5sclose_f(s2, e2)
  end function select_runs

  !> Release the dataspaces of rows and empty it.
  subroutine free_rows(rows)
    type(rows_t), intent(inout) :: rows
    integer :: k, err

    do k = lbound(rows%fspace, 1), ubound(rows%fspace, 1)
      if (rows%fspace(k) /= -1) call h5sclose_f(rows%fspace(k), err)
      if (rows%mspace(k) /= -1) call h5sclose_f(rows%mspace(k), err)
    end do
    rows = rows_t()
  end subroutine free_rows

  !> An int32 (ints) or float64 (reals) dataset of the rows of one kind
  !> (see write_rows). Assumed-size dummies give the contiguous buffer that
  !> c_loc needs, whatever the rank (a copy is made only if the caller
  !> passed a non-contiguous section).
  subroutine write_data(w, loc, name, which, width, ok, errmsg, ints, reals)
    type(field_writer_t), intent(inout) :: w
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer, intent(in) :: which, width
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer(ik), intent(in), target, optional :: ints(*)
    real(rk), intent(in), target, optional :: reals(*)
    integer(ik), target :: idummy(1)
    real(rk), target :: rdummy(1)
    logical :: none

    ! c_loc needs an array that is not zero-sized: a rank without rows
    ! passes a dummy that is never read.
    if (which == on_nodes) then
      none = w%node_rows%n == 0
    else
      none = w%elem_rows%n == 0
    end if
    if (present(ints)) then
      if (none) then
        call write_rows(w, loc, name, H5T_STD_I32LE, h5kind_to_type(ik, H5_INTEGER_KIND), &
                        which, width, c_loc(idummy), ok, errmsg)
      else
        call write_rows(w, loc, name, H5T_STD_I32LE, h5kind_to_type(ik, H5_INTEGER_KIND), &
                        which, width, c_loc(ints), ok, errmsg)
      end if
    else
      if (none) then
        call write_rows(w, loc, name, H5T_IEEE_F64LE, h5kind_to_type(rk, H5_REAL_KIND), &
                        which, width, c_loc(rdummy), ok, errmsg)
      else
        call write_rows(w, loc, name, H5T_IEEE_F64LE, h5kind_to_type(rk, H5_REAL_KIND), &
                        which, width, c_loc(reals), ok, errmsg)
      end if
    end if
  end subroutine write_data

  !> Create and write one scalar attribute from the buffer at buf
  !> (collective: every rank passes the same value).
  subroutine write_attr(w, loc, name, ftype, mtype, buf, ok, errmsg)
    type(field_writer_t), intent(in) :: w
    integer(hid_t), intent(in) :: loc, ftype, mtype
    character(len=*), intent(in) :: name
    type(c_ptr), intent(in) :: buf
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer(hid_t) :: sid, aid
    integer :: err, e2

    ok = .false.
    errmsg = ''
    call h5screate_f(H5S_SCALAR_F, sid, err)
    if (err < 0) then
      errmsg = op_err(w, 'create dataspace for attribute '//name)
      return
    end if
    call h5acreate_f(loc, name, ftype, sid, aid, err)
    if (err < 0) then
      call h5sclose_f(sid, e2)
      errmsg = op_err(w, 'create attribute '//name)
      return
    end if
    call h5awrite_f(aid, mtype, buf, err)
    if (err < 0) errmsg = op_err(w, 'write attribute '//name)
    ! after a failed write the first error is kept and the closes are best effort
    call h5aclose_f(aid, e2)
    if (err >= 0) err = e2
    call h5sclose_f(sid, e2)
    if (len(errmsg) > 0) return
    ok = err >= 0 .and. e2 >= 0
    if (.not. ok) errmsg = op_err(w, 'close attribute '//name)
  end subroutine write_attr

  !> One scalar numeric attribute: int32, int64 or float64 by the type of val.
  subroutine attr_num(w, loc, name, val, ok, errmsg)
    type(field_writer_t), intent(in) :: w
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    class(*), intent(in) :: val
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer(ik), target :: vi
    integer(i8), target :: v8
    real(rk), target :: vr
    integer(hid_t) :: ftype, mtype
    type(c_ptr) :: buf

    select type (val)
    type is (integer(ik))
      vi = val; buf = c_loc(vi); ftype = H5T_STD_I32LE; mtype = h5kind_to_type(ik, H5_INTEGER_KIND)
    type is (integer(i8))
      v8 = val; buf = c_loc(v8); ftype = H5T_STD_I64LE; mtype = h5kind_to_type(i8, H5_INTEGER_KIND)
    type is (real(rk))
      vr = val; buf = c_loc(vr); ftype = H5T_IEEE_F64LE; mtype = h5kind_to_type(rk, H5_REAL_KIND)
    class default
      ok = .false.
      errmsg = op_err(w, 'attribute '//name//' of a type other than int32, int64, float64')
      return
    end select
    call write_attr(w, loc, name, ftype, mtype, buf, ok, errmsg)
  end subroutine attr_num

  !> Variable-length UTF-8 string attribute.  Variable length because the
  !> deck can exceed the 64 KiB limit of a fixed-size attribute in the
  !> default file format, and h5py returns it as str rather than bytes.
  subroutine attr_str(w, loc, name, val, ok, errmsg)
    type(field_writer_t), intent(in) :: w
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name, val
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    character(kind=c_char), allocatable, target :: cbuf(:)
    type(c_ptr), target :: ptr(1)
    integer(hid_t) :: tid
    integer :: err, e2, i

    ok = .false.
    errmsg = ''
    allocate(cbuf(len(val) + 1))
    do i = 1, len(val)
      cbuf(i) = val(i:i)
    end do
    cbuf(len(val) + 1) = c_null_char
    ptr(1) = c_loc(cbuf)

    call h5tcopy_f(H5T_STRING, tid, err)
    if (err >= 0) call h5tset_cset_f(tid, H5T_CSET_UTF8_F, err)
    if (err < 0) then
      errmsg = op_err(w, 'create string type for attribute '//name)
      return
    end if
    call write_attr(w, loc, name, tid, tid, c_loc(ptr), ok, errmsg)
    call h5tclose_f(tid, e2)
  end subroutine attr_str

  !> Overwrite an existing scalar int32 attribute (collective).
  subroutine update_attr_int(w, loc, name, val, ok, errmsg)
    type(field_writer_t), intent(in) :: w
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer(ik), intent(in) :: val
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer(ik), target :: v
    integer(hid_t) :: aid
    integer :: err, e2

    ok = .false.
    errmsg = ''
    v = val
    call h5aopen_f(loc, name, aid, err)
    if (err < 0) then
      errmsg = op_err(w, 'open attribute '//name)
      return
    end if
    call h5awrite_f(aid, h5kind_to_type(ik, H5_INTEGER_KIND), c_loc(v), err)
    call h5aclose_f(aid, e2)
    ok = err >= 0 .and. e2 >= 0
    if (.not. ok) errmsg = op_err(w, 'write attribute '//name)
  end subroutine update_attr_int

  !> Read the scalar attribute obj@name (obj relative to loc) into the
  !> buffer at buf, converted to the memory type mtype.
  subroutine read_attr(w, loc, obj, name, mtype, buf, ok, errmsg)
    type(field_writer_t), intent(in) :: w
    integer(hid_t), intent(in) :: loc, mtype
    character(len=*), intent(in) :: obj, name
    type(c_ptr), intent(in) :: buf
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer(hid_t) :: aid
    integer :: err, e2
    type(c_ptr) :: p   ! h5aread_f wants a definable c_ptr

    ok = .false.
    errmsg = ''
    call h5aopen_by_name_f(loc, obj, name, aid, err)
    if (err < 0) then
      errmsg = 'field_output: "'//w%h5_path//'" has no attribute '//obj//'@'//name
      return
    end if
    p = buf
    call h5aread_f(aid, mtype, p, err)
    call h5aclose_f(aid, e2)
    ok = err >= 0
    if (.not. ok) errmsg = op_err(w, 'read attribute '//obj//'@'//name)
  end subroutine read_attr

  ! ------------------------------------------------------------ utilities

  !> Local time as ISO-8601, e.g. 2024-05-01T12:34:56+02:00.
  function iso8601_now() result(s)
    character(len=:), allocatable :: s
    character(len=8) :: d
    character(len=10) :: t
    character(len=5) :: z

    call date_and_time(date=d, time=t, zone=z)
    s = d(1:4)//'-'//d(5:6)//'-'//d(7:8)//'T'//t(1:2)//':'//t(3:4)//':'//t(5:6)
    if (len_trim(z) == 5) then
      s = s//z(1:3)//':'//z(4:5)
    end if
  end function iso8601_now

end module udar_field_output
