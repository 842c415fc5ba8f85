!> Time-series field output: one HDF5 file plus an XDMF (.xmf) index that
!> ParaView opens directly.  Layout is specified in doc/output-format.md;
!> Python readers depend on it, so change both together.
!>
!> Serial by design: the caller gathers global arrays and calls this on one
!> rank only.  No MPI is used here.
!>
!> Life cycle:
!>   fw_open -> { fw_begin_step -> fw_node_vector/fw_node_scalar/fw_elem_scalar
!>   -> fw_end_step }* -> fw_close
!> A step is committed (counted in /steps@count and listed in the .xmf) only
!> by fw_end_step.
module udar_field_output
  use, intrinsic :: iso_c_binding, only: c_char, c_int, c_ptr, c_loc, c_null_char
  use udar_kinds, only: rk, ik, i8, max_name_len
  use udar_strings, only: is_letter, is_digit, dir_name, base_name
  use hdf5
  implicit none
  private

  public :: fw_open, fw_begin_step, fw_node_vector, fw_node_scalar, &
            fw_elem_scalar, fw_end_step, fw_close

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
  end type step_rec_t

  type, public :: field_writer_t
    private
    logical :: is_open = .false.
    logical :: in_step = .false.
    integer(hid_t) :: file_id = -1
    integer(hid_t) :: step_gid = -1        ! group of the step being written
    character(len=:), allocatable :: h5_path, xmf_path
    character(len=:), allocatable :: h5_ref ! h5 base name, as referenced from the .xmf
    character(len=:), allocatable :: title
    integer(ik) :: n_nodes = 0, n_elems = 0
    integer :: n_steps = 0                  ! committed steps
    type(step_rec_t), allocatable :: steps(:)
    type(step_rec_t) :: cur                 ! step being written
    real(rk), allocatable :: buf(:,:)       ! (3,n_nodes) transpose buffer
  end type field_writer_t

  !> cycle may be a default (int32) or int64 counter; stored as int64.
  interface fw_begin_step
    module procedure fw_begin_step_ik, fw_begin_step_i8
  end interface fw_begin_step

  interface
    function c_rename(old, new) bind(c, name='rename') result(r)
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: old(*), new(*)
      integer(c_int) :: r
    end function c_rename
    function c_remove(path) bind(c, name='remove') result(r)
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int) :: r
    end function c_remove
  end interface

contains

  ! ---------------------------------------------------------------- public

  !> Create (truncate) the HDF5 file and write the run header and the mesh.
  !> Removes a stale .xmf of the same name: the .xmf appears at the first
  !> fw_end_step and always lists only committed steps.
  subroutine fw_open(w, h5_path, xmf_path, node_id, elem_id, conn, part_id, x0, &
                     deck_text, version, title, n_ranks, ok, errmsg)
    type(field_writer_t), intent(inout) :: w
    character(len=*), intent(in) :: h5_path, xmf_path
    integer(ik), intent(in) :: node_id(:), elem_id(:), conn(:,:), part_id(:)
    real(rk), intent(in) :: x0(:,:)
    character(len=*), intent(in) :: deck_text, version, title
    integer(ik), intent(in) :: n_ranks
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg

    integer :: err, nn, ne, i, j
    integer(hid_t) :: gid
    integer(ik), allocatable :: ibuf(:,:)
    integer(c_int) :: irc

    ok = .false.
    errmsg = ''
    nn = size(node_id)
    ne = size(elem_id)
    ! the first problem with the call, if any
    if (w%is_open) then
      errmsg = 'field_output: fw_open called on a writer that is already open ('// &
               w%h5_path//')'
    else if (nn < 1 .or. ne < 1) then
      errmsg = 'field_output: fw_open needs at least one node and one element'
    else if (any(shape(conn) /= [ne, 4])) then
      errmsg = 'field_output: conn must have shape (n_elems,4)'
    else if (size(part_id) /= ne) then
      errmsg = 'field_output: part_id must have size n_elems'
    else if (any(shape(x0) /= [nn, 3])) then
      errmsg = 'field_output: x0 must have shape (n_nodes,3)'
    else if (any(conn < 1) .or. any(conn > nn)) then
      errmsg = 'field_output: conn holds node indices outside 1..n_nodes'
    else if (len_trim(h5_path) == 0 .or. len_trim(xmf_path) == 0) then
      errmsg = 'field_output: empty output path'
    else if (trim(h5_path) == trim(xmf_path)) then
      errmsg = 'field_output: h5 and xmf paths are the same: '//trim(h5_path)
    else if (dir_name(trim(h5_path)) /= dir_name(trim(xmf_path))) then
      ! The .xmf refers to the h5 by base name, so both must share a directory.
      errmsg = 'field_output: "'//trim(h5_path)//'" and "'//trim(xmf_path)// &
               '" must be in the same directory (the .xmf references the h5 by base name)'
    end if
    if (len(errmsg) > 0) return

    w%h5_path = trim(h5_path)
    w%xmf_path = trim(xmf_path)
    w%h5_ref = base_name(w%h5_path)
    w%title = title
    w%n_nodes = int(nn, ik)
    w%n_elems = int(ne, ik)
    w%n_steps = 0

    ! Fortran HDF5 constants are only valid after h5open_f; calling it again
    ! is harmless and protects against another module having called h5close_f.
    call h5open_f(err)
    if (err < 0) then
      errmsg = 'field_output: HDF5 library initialisation (h5open_f) failed'
      return
    end if
    ! Errors are reported through errmsg only.
    call h5eset_auto_f(0, err)

    call h5fcreate_f(w%h5_path, H5F_ACC_TRUNC_F, w%file_id, err)
    if (err < 0) then
      errmsg = op_err(w, 'create file (h5fcreate_f)')
      w%file_id = -1
      return
    end if
    w%is_open = .true.

    ! Stale index files from an earlier run would point at the new h5.
    irc = c_remove(w%xmf_path//c_null_char)
    irc = c_remove(w%xmf_path//'.tmp'//c_null_char)

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
      call write_data(w, gid, 'node_id', [int(nn, hsize_t)], ok, errmsg, ints=node_id)
      if (ok) call write_data(w, gid, 'elem_id', [int(ne, hsize_t)], ok, errmsg, ints=elem_id)
      if (ok) call write_data(w, gid, 'part_id', [int(ne, hsize_t)], ok, errmsg, ints=part_id)
      if (ok) then
        ! 0-based and transposed: C-order (n_elems,4) is what XDMF reads.
        allocate(ibuf(4, ne))
        do j = 1, 4
          do i = 1, ne
            ibuf(j, i) = conn(i, j) - 1_ik
          end do
        end do
        call write_data(w, gid, 'connectivity', [4_hsize_t, int(ne, hsize_t)], ok, errmsg, ints=ibuf)
        deallocate(ibuf)
      end if
      if (ok) then
        allocate(w%buf(3, nn))
        call write_vector(w, gid, 'x0', x0, ok, errmsg)
      end if
      call end_group(w, gid, 'mesh', ok, errmsg); if (.not. ok) exit setup

      call make_group(w, w%file_id, 'steps', gid, ok, errmsg); if (.not. ok) exit setup
      call attr_num(w, gid, 'count', 0_ik, ok, errmsg)
      call end_group(w, gid, 'steps', ok, errmsg); if (.not. ok) exit setup

      call h5fflush_f(w%file_id, H5F_SCOPE_GLOBAL_F, err)
      if (err < 0) then
        ok = .false.
        errmsg = op_err(w, 'flush (h5fflush_f)')
        exit setup
      end if
      return
    end block setup

    ! Leave the writer closed on failure so the caller can retry or abort.
    ok = .false.
    call fw_close(w)
  end subroutine fw_open

  !> Open output step number n_steps (group /steps/NNNNNN) and write the
  !> current coordinates.
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
    if (size(x, 1) /= w%n_nodes .or. size(x, 2) /= 3) then
      errmsg = op_err(w, 'fw_begin_step: x must have shape (n_nodes,3)')
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
    if (.not. allocated(w%cur%fields)) allocate(w%cur%fields(8))

    call attr_num(w, w%step_gid, 'time', time, ok, errmsg); if (.not. ok) return
    call attr_num(w, w%step_gid, 'cycle', cycle, ok, errmsg); if (.not. ok) return
    call write_vector(w, w%step_gid, 'coordinates', x, ok, errmsg)
  end subroutine fw_begin_step_i8

  !> Nodal vector field a(n_nodes,3), stored C-order (n_nodes,3).
  subroutine fw_node_vector(w, name, a, ok, errmsg)
    type(field_writer_t), intent(inout) :: w
    character(len=*), intent(in) :: name
    real(rk), intent(in) :: a(:,:)
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    call write_field(w, name, fk_node_vector, size(a, 1) == w%n_nodes .and. size(a, 2) == 3, &
                     ok, errmsg, vector=a)
  end subroutine fw_node_vector

  !> Nodal scalar field a(n_nodes).
  subroutine fw_node_scalar(w, name, a, ok, errmsg)
    type(field_writer_t), intent(inout) :: w
    character(len=*), intent(in) :: name
    real(rk), intent(in) :: a(:)
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    call write_field(w, name, fk_node_scalar, size(a) == w%n_nodes, ok, errmsg, scalar=a)
  end subroutine fw_node_scalar

  !> Element (cell) scalar field a(n_elems).
  subroutine fw_elem_scalar(w, name, a, ok, errmsg)
    type(field_writer_t), intent(inout) :: w
    character(len=*), intent(in) :: name
    real(rk), intent(in) :: a(:)
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    call write_field(w, name, fk_elem_scalar, size(a) == w%n_elems, ok, errmsg, scalar=a)
  end subroutine fw_elem_scalar

  !> Commit the current step: close its group, bump /steps@count, flush the
  !> file and atomically replace the .xmf.
  subroutine fw_end_step(w, ok, errmsg)
    type(field_writer_t), intent(inout) :: w
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg

    integer :: err
    integer(hid_t) :: gid
    type(step_rec_t), allocatable :: tmp(:)

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
    if (.not. allocated(w%steps)) allocate(w%steps(16))
    if (w%n_steps >= size(w%steps)) then
      allocate(tmp(2*size(w%steps)))
      tmp(1:w%n_steps) = w%steps(1:w%n_steps)
      call move_alloc(tmp, w%steps)
    end if
    w%n_steps = w%n_steps + 1
    w%steps(w%n_steps) = w%cur
    w%steps(w%n_steps)%fields = w%cur%fields(1:w%cur%n_fields)

    call h5gopen_f(w%file_id, 'steps', gid, err)
    if (err < 0) then
      errmsg = op_err(w, 'open group /steps')
      return
    end if
    call update_attr_int(w, gid, 'count', int(w%n_steps, ik), ok, errmsg)
    call end_group(w, gid, 'steps', ok, errmsg); if (.not. ok) return

    ! Flush before publishing the .xmf so it never names unwritten data.
    call h5fflush_f(w%file_id, H5F_SCOPE_GLOBAL_F, err)
    if (err < 0) then
      ok = .false.
      errmsg = op_err(w, 'flush (h5fflush_f)')
      return
    end if

    call write_xmf(w, ok, errmsg)
  end subroutine fw_end_step

  !> Close the file and reset the writer.  Safe on a writer that is not open.
  !> A step begun but not ended is unlinked: it was never committed.
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
    w%is_open = .false.
    w%in_step = .false.
    w%file_id = -1
    w%step_gid = -1
    w%n_nodes = 0
    w%n_elems = 0
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
  !> (fits: the array has the shape of its kind), the dataset, the record.
  subroutine write_field(w, name, kind, fits, ok, errmsg, vector, scalar)
    type(field_writer_t), intent(inout) :: w
    character(len=*), intent(in) :: name
    integer, intent(in) :: kind
    logical, intent(in) :: fits
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    real(rk), intent(in), optional :: vector(:,:), scalar(:)

    call check_field(w, name, ok, errmsg); if (.not. ok) return
    if (.not. fits) then
      ok = .false.
      select case (kind)
      case (fk_node_vector)
        errmsg = op_err(w, 'fw_node_vector "'//trim(name)//'": shape must be (n_nodes,3)')
      case (fk_node_scalar)
        errmsg = op_err(w, 'fw_node_scalar "'//trim(name)//'": size must be n_nodes')
      case default
        errmsg = op_err(w, 'fw_elem_scalar "'//trim(name)//'": size must be n_elems')
      end select
      return
    end if
    if (present(vector)) then
      call write_vector(w, w%step_gid, trim(name), vector, ok, errmsg)
    else
      call write_data(w, w%step_gid, trim(name), [int(size(scalar), hsize_t)], ok, errmsg, &
                      reals=scalar)
    end if
    if (ok) call add_field(w, trim(name), kind)
  end subroutine write_field

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
    call write_data(w, loc, name, [3_hsize_t, int(size(a, 1), hsize_t)], ok, errmsg, reals=w%buf)
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
    integer(c_int) :: irc

    ok = .false.
    errmsg = ''
    tmp_path = w%xmf_path//'.tmp'
    h5 = xml_escape(w%h5_ref)
    write(sn, '(i0)') w%n_nodes
    write(se, '(i0)') w%n_elems

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
      '    <Grid Name="'//xml_escape(w%title)// &
      '" GridType="Collection" CollectionType="Temporal">'

    do s = 1, w%n_steps
      if (ios /= 0) exit
      associate (st_rec => w%steps(s))
        write(st, '(es24.16e3)') st_rec%time
        write(u, '(a)', iostat=ios, iomsg=iomsg) &
          '      <Grid Name="step_'//st_rec%group//'" GridType="Uniform">'
        if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) &
          '        <Time Value="'//trim(adjustl(st))//'"/>'
        if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) &
          '        <Topology TopologyType="Tetrahedron" NumberOfElements="'//trim(se)// &
          '" NodesPerElement="4">'
        if (ios == 0) write(u, '(a)', iostat=ios, iomsg=iomsg) &
          '          <DataItem Dimensions="'//trim(se)//' 4" NumberType="Int" Precision="4" Format="HDF">'// &
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

    irc = c_rename(tmp_path//c_null_char, w%xmf_path//c_null_char)
    if (irc /= 0) then
      errmsg = 'field_output: rename "'//tmp_path//'" -> "'//w%xmf_path//'" failed'
      return
    end if
    ok = .true.
  end subroutine write_xmf

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

  !> Create and write one dataset (dims given, in Fortran order: HDF5
  !> reverses them, so Fortran (3,n) is C (n,3)) or one scalar attribute (no
  !> dims) from the buffer at buf. The two differ only in the HDF5 calls.
  subroutine write_object(w, loc, name, ftype, mtype, buf, ok, errmsg, dims)
    type(field_writer_t), intent(in) :: w
    integer(hid_t), intent(in) :: loc, ftype, mtype
    character(len=*), intent(in) :: name
    type(c_ptr), intent(in) :: buf
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer(hsize_t), intent(in), optional :: dims(:)
    character(len=:), allocatable :: what
    integer(hid_t) :: sid, oid
    integer :: err, e2

    ok = .false.
    errmsg = ''
    if (present(dims)) then
      what = 'dataset '//name
      call h5screate_simple_f(size(dims), dims, sid, err)
    else
      what = 'attribute '//name
      call h5screate_f(H5S_SCALAR_F, sid, err)
    end if
    if (err < 0) then
      errmsg = op_err(w, 'create dataspace for '//what)
      return
    end if
    if (present(dims)) then
      call h5dcreate_f(loc, name, ftype, sid, oid, err)
    else
      call h5acreate_f(loc, name, ftype, sid, oid, err)
    end if
    if (err < 0) then
      call h5sclose_f(sid, e2)
      errmsg = op_err(w, 'create '//what)
      return
    end if
    if (present(dims)) then
      call h5dwrite_f(oid, mtype, buf, err)
    else
      call h5awrite_f(oid, mtype, buf, err)
    end if
    if (err < 0) errmsg = op_err(w, 'write '//what)
    ! after a failed write the first error is kept and the closes are best effort
    if (present(dims)) then
      call h5dclose_f(oid, e2)
    else
      call h5aclose_f(oid, e2)
    end if
    if (err >= 0) err = e2
    call h5sclose_f(sid, e2)
    if (len(errmsg) > 0) return
    ok = err >= 0 .and. e2 >= 0
    if (.not. ok) errmsg = op_err(w, 'close '//what)
  end subroutine write_object

  !> An int32 (ints) or float64 (reals) dataset of shape dims. Assumed-size
  !> dummies give the contiguous buffer that c_loc needs, whatever the rank
  !> (a copy is made only if the caller passed a non-contiguous section).
  subroutine write_data(w, loc, name, dims, ok, errmsg, ints, reals)
    type(field_writer_t), intent(in) :: w
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer(hsize_t), intent(in) :: dims(:)
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer(ik), intent(in), target, optional :: ints(*)
    real(rk), intent(in), target, optional :: reals(*)
    if (present(ints)) then
      call write_object(w, loc, name, H5T_STD_I32LE, h5kind_to_type(ik, H5_INTEGER_KIND), &
                        c_loc(ints), ok, errmsg, dims)
    else
      call write_object(w, loc, name, H5T_IEEE_F64LE, h5kind_to_type(rk, H5_REAL_KIND), &
                        c_loc(reals), ok, errmsg, dims)
    end if
  end subroutine write_data

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
    call write_object(w, loc, name, ftype, mtype, buf, ok, errmsg)
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
    call write_object(w, loc, name, tid, tid, c_loc(ptr), ok, errmsg)
    call h5tclose_f(tid, e2)
  end subroutine attr_str

  !> Overwrite an existing scalar int32 attribute.
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
