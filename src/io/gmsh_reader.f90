!> Reader for gmsh meshes: MSH 4.1 (ASCII and binary) and MSH 2.2 (ASCII).
!>
!> The whole file is read into memory once and parsed with a byte cursor.
!> This is much faster than formatted I/O on large meshes and lets the ASCII
!> and binary variants share the section logic.  Only what the solver needs
!> is kept: for a 3D mesh, linear tetrahedra in physical volume groups and
!> linear triangles in physical surface groups; for a 2D one (plane z = 0),
!> linear triangles in physical surface groups and 2-node lines in physical
!> curve groups.  Errors are returned, never printed.
module udar_gmsh
  use, intrinsic :: iso_fortran_env, only: int32, int64
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use udar_kinds, only: rk, i8, max_name_len
  use udar_strings, only: itoa, r2s
  use udar_file_kind, only: not_regular_file
  implicit none
  private

  public :: gmsh_read

  type, public :: gmsh_group_t
    integer :: dim = 0, tag = 0
    character(len=max_name_len) :: name = ''
  end type gmsh_group_t

  !> The mesh of one dimension dim (3: solid, 2: planar or axisymmetric):
  !> its cells (4-node tetrahedra in physical volume groups, or 3-node
  !> triangles in physical surface groups) and its boundary facets
  !> (triangles in physical surface groups, or 2-node lines in physical curve
  !> groups), one row per (facet, group).
  type, public :: gmsh_mesh_t
    integer :: dim = 3
    integer :: n_nodes = 0, n_cells = 0, n_facets = 0, n_groups = 0
    integer, allocatable :: node_tag(:)     !< (n_nodes) gmsh node tags, ascending
    real(rk), allocatable :: x(:,:)         !< (n_nodes,3) coordinates * scale
    integer, allocatable :: cell_tag(:)     !< (n_cells) gmsh element tags, ascending
    integer, allocatable :: cell(:,:)       !< (n_cells,dim+1) node indices, positively oriented
    integer, allocatable :: cell_group(:)   !< (n_cells) index into groups(:) (of dimension dim)
    integer, allocatable :: facet(:,:)      !< (n_facets,dim) node indices of the physical groups' facets
    integer, allocatable :: facet_group(:)  !< (n_facets) index into groups(:) (of dimension dim-1)
    type(gmsh_group_t), allocatable :: groups(:)  !< physical groups of dims dim-1 and dim
    integer :: n_inverted = 0               !< cells reoriented at read time
  end type gmsh_mesh_t

  integer, parameter :: fmt_v22 = 22, fmt_v41 = 41
  ! By dimension k = 1, 2, 3: the linear simplex kept (gmsh type), its name,
  ! the entity it meshes and its measure, for messages (simplex_plural(k)(8:)
  ! is the plural without the node count).
  integer, parameter :: linear_type(3) = [1, 2, 4]
  character(len=*), parameter :: simplex_name(3) = [character(len=11) :: &
       'line', 'triangle', 'tetrahedron']
  character(len=*), parameter :: simplex_plural(3) = [character(len=17) :: &
       '2-node lines', '3-node triangles', '4-node tetrahedra']
  character(len=*), parameter :: entity_name(3) = [character(len=7) :: 'curve', 'surface', 'volume']
  character(len=*), parameter :: physical_cmd(3) = [character(len=16) :: &
       'Physical Curve', 'Physical Surface', 'Physical Volume']
  character(len=*), parameter :: measure_name(3) = [character(len=6) :: 'length', 'area', 'volume']
  integer, parameter :: max_listed = 20     ! element tags listed in an error message
  ! sizes of binary MSH 4.1 values
  integer(i8), parameter :: int_bytes = 4, size_bytes = 8, real_bytes = 8
  real(rk), parameter :: degenerate_tol = 1.0e-12_rk
  real(rk), parameter :: max_coord = 1.0e30_rk   ! m: (6 V)**2 ~ L**6 stays finite

  ! Exact powers of ten: a decimal with <= 2**53 mantissa and |exponent| <= 22
  ! converts with one correctly rounded operation (Clinger's fast path).
  real(rk), parameter :: p10(0:22) = [ 1.0e0_rk,  1.0e1_rk,  1.0e2_rk,  1.0e3_rk, &
       1.0e4_rk,  1.0e5_rk,  1.0e6_rk,  1.0e7_rk,  1.0e8_rk,  1.0e9_rk, 1.0e10_rk, &
      1.0e11_rk, 1.0e12_rk, 1.0e13_rk, 1.0e14_rk, 1.0e15_rk, 1.0e16_rk, 1.0e17_rk, &
      1.0e18_rk, 1.0e19_rk, 1.0e20_rk, 1.0e21_rk, 1.0e22_rk ]
  integer(i8), parameter :: two53 = 9007199254740992_i8
  ! Physical groups are identified by (dim, tag) packed into one sortable key.
  integer(i8), parameter :: dim_shift = 4294967296_i8

  !> Byte cursor over the file contents.
  type :: cursor_t
    character(len=:), allocatable :: buf
    integer(i8) :: pos = 1, n = 0
    logical :: binary = .false.
    logical :: bad = .false.
    character(len=:), allocatable :: msg
  end type cursor_t

  !> Curves, surfaces or volumes of a MSH 4.1 $Entities section.
  type :: entity_list_t
    integer :: n = 0
    integer, allocatable :: tag(:)
    integer, allocatable :: first(:)   ! (n+1) offsets into phys (CSR)
    integer, allocatable :: phys(:)
    integer(i8), allocatable :: skey(:) ! sorted tags, for lookup by tag
    integer, allocatable :: sidx(:)
  end type entity_list_t

  !> Elements of one kind (lines, triangles or tets) as read, before tags are resolved.
  type :: elem_list_t
    integer :: nv = 0                         ! nodes per element
    integer :: n = 0
    ! ref: entity tag (4.1) or physical tag (2.2)
    integer, allocatable :: tag(:), ref(:), node(:,:)   ! node(nv,n): node tags
  end type elem_list_t

  !> Everything gathered while parsing, before tags are resolved.
  type :: raw_t
    integer :: version = 0
    logical :: have_nodes = .false., have_elements = .false.
    integer :: n_names = 0
    integer, allocatable :: name_dim(:), name_tag(:)
    character(len=max_name_len), allocatable :: name_str(:)
    integer :: dim = 3                        ! of the mesh asked for (2 or 3)
    type(entity_list_t) :: ents(3)            ! curves, surfaces, volumes
    integer :: nn = 0
    integer, allocatable :: ntag(:)
    real(rk), allocatable :: nx(:,:)          ! (3,nn) as in the file
    ! lines, triangles, tets: those of dimensions dim-1 and dim are kept
    type(elem_list_t) :: elems(3) = [elem_list_t(nv=2), elem_list_t(nv=3), elem_list_t(nv=4)]
    ! MSH 2.2: groups used by elements of other types, so that the group list
    ! does not depend on the format (4.1 gets them from $Entities)
    integer :: n_keys = 0
    integer(i8), allocatable :: keys(:)
  end type raw_t

contains

  ! ==========================================================================
  !  Public entry point
  ! ==========================================================================

  !> Read a gmsh mesh file as a mesh of dimension dim (3, the default:
  !> tetrahedra; 2: triangles in the plane z = 0).  On failure ok is .false.,
  !> mesh is empty and errmsg names the file and the problem.
  subroutine gmsh_read(path, scale, mesh, ok, errmsg, dim)
    character(len=*), intent(in) :: path
    real(rk), intent(in) :: scale
    type(gmsh_mesh_t), intent(out) :: mesh
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer, intent(in), optional :: dim

    type(cursor_t) :: c
    type(raw_t) :: raw
    character(len=:), allocatable :: msg

    ok = .false.
    errmsg = ''
    if (.not. (ieee_is_finite(scale) .and. scale > 0.0_rk)) then
      errmsg = 'gmsh_read: '//trim(path)//': scale factor must be positive and finite'
      return
    end if
    if (present(dim)) raw%dim = dim
    if (raw%dim /= 2 .and. raw%dim /= 3) then
      errmsg = 'gmsh_read: '//trim(path)//': mesh dimension '//itoa(raw%dim)//' asked for (must be 2 or 3)'
      return
    end if
    mesh%dim = raw%dim

    call load_file(path, c)
    if (.not. c%bad) call parse_file(c, raw)
    if (c%bad) then
      errmsg = 'gmsh_read: '//trim(path)//': '//c%msg
      return
    end if
    deallocate(c%buf)    ! the text is no longer needed: free it before building

    call build_mesh(raw, scale, mesh, msg)
    if (len(msg) > 0) then
      errmsg = 'gmsh_read: '//trim(path)//': '//msg
      call clear_mesh(mesh)
      return
    end if
    ok = .true.
  end subroutine gmsh_read

  ! ==========================================================================
  !  File loading and section dispatch
  ! ==========================================================================

  subroutine load_file(path, c)
    character(len=*), intent(in) :: path
    type(cursor_t), intent(inout) :: c
    integer :: u, ios
    integer(i8) :: fsize
    logical :: exists
    character(len=256) :: iomsg
    character(len=:), allocatable :: what

    inquire(file=path, exist=exists)
    if (.not. exists) then
      call fail(c, 'file not found')
      return
    end if
    ! a FIFO or a terminal would block the OPEN or the READ forever
    what = not_regular_file(path)
    if (len(what) > 0) then
      call fail(c, 'it is '//what//', not a regular file')
      return
    end if
    open(newunit=u, file=path, access='stream', form='unformatted', status='old', &
         action='read', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      call fail(c, 'cannot open file: '//trim(iomsg))
      return
    end if
    inquire(unit=u, size=fsize)
    if (fsize <= 0) then
      close(u)
      call fail(c, 'file is empty (or its size cannot be determined)')
      return
    end if
    allocate(character(len=fsize) :: c%buf)
    read(u, iostat=ios, iomsg=iomsg) c%buf
    close(u)
    if (ios /= 0) then
      call fail(c, 'read error: '//trim(iomsg))
      return
    end if
    c%n = fsize
    c%pos = 1
  end subroutine load_file

  subroutine parse_file(c, raw)
    type(cursor_t), intent(inout) :: c
    type(raw_t), intent(inout) :: raw
    character(len=:), allocatable :: name
    integer(i8) :: p0, k

    name = ''
    do
      call skip_ws(c)
      if (c%pos > c%n) exit
      if (c%buf(c%pos:c%pos) /= '$') then
        if (raw%version == 0) then
          call fail(c, 'not a gmsh MSH file (it does not start with $MeshFormat)')
        else
          call fail(c, 'unexpected data "'//token_at(c, c%pos)//'" outside a section')
        end if
        return
      end if
      p0 = c%pos + 1
      c%pos = token_end(c, c%pos)
      name = c%buf(p0:c%pos-1)
      call skip_line(c)
      if (raw%version == 0 .and. name /= 'MeshFormat') then
        call fail(c, 'not a gmsh MSH file (it does not start with $MeshFormat)')
        return
      end if

      select case (name)
      case ('MeshFormat')
        call parse_format(c, raw)
      case ('PhysicalNames')
        call parse_names(c, raw)
      case ('Entities')
        if (raw%version == fmt_v41) then
          call parse_entities(c, raw)
        else
          call skip_section(c, name)
        end if
      case ('Nodes')       ! (the version is known: $MeshFormat came first)
        if (raw%have_nodes) call fail(c, 'more than one $Nodes section')
        raw%have_nodes = .true.
        if (raw%version == fmt_v41) call parse_nodes_41(c, raw)
        if (raw%version == fmt_v22) call parse_nodes_22(c, raw)
      case ('Elements')
        if (raw%have_elements) call fail(c, 'more than one $Elements section')
        raw%have_elements = .true.
        if (raw%version == fmt_v41) call parse_elements_41(c, raw)
        if (raw%version == fmt_v22) call parse_elements_22(c, raw)
      case default
        ! $Periodic, $NodeData, $Comments, $PartitionedEntities...: not needed
        call skip_section(c, name)
      end select
      if (c%bad) return

      ! Every section must close where its declared counts say it ends:
      ! this catches wrong counts and truncated files.
      call skip_ws(c)
      k = len('$End'//name, kind=i8)
      if (c%pos > c%n) then
        call fail(c, 'unexpected end of file: $End'//name//' missing (file truncated?)')
        return
      end if
      if (c%pos + k - 1 > c%n) then
        call fail(c, 'expected $End'//name//' (file truncated or counts inconsistent)')
        return
      end if
      if (c%buf(c%pos:c%pos+k-1) /= '$End'//name) then
        call fail(c, 'expected $End'//name//' but found "'//token_at(c, c%pos)// &
                  '" (section counts inconsistent with the data?)')
        return
      end if
      c%pos = c%pos + k
      call skip_line(c)
    end do

    if (raw%version == 0) then
      call fail(c, 'not a gmsh MSH file (no $MeshFormat section)')
    else if (.not. raw%have_nodes) then
      call fail(c, 'no $Nodes section')
    else if (.not. raw%have_elements) then
      call fail(c, 'no $Elements section')
    end if
  end subroutine parse_file

  subroutine skip_section(c, name)
    type(cursor_t), intent(inout) :: c
    character(len=*), intent(in) :: name
    integer(i8) :: k
    k = index(c%buf(c%pos:c%n), '$End'//name, kind=i8)
    if (k == 0) then
      call fail(c, 'section $'//name//' is not terminated (file truncated?)')
    else
      c%pos = c%pos + k - 1
    end if
  end subroutine skip_section

  subroutine parse_format(c, raw)
    type(cursor_t), intent(inout) :: c
    type(raw_t), intent(inout) :: raw
    character(len=:), allocatable :: ver
    integer(i8) :: ftype, dsize
    integer :: one

    call skip_ws(c)
    ver = token_at(c, c%pos)
    call skip_token(c, 'format version')
    call get_i8(c, ftype, 'file type')
    call get_i8(c, dsize, 'data size')
    if (c%bad) return
    if (ver == '4.1') then
      raw%version = fmt_v41
    else if (ver == '2.2' .or. ver == '2.1' .or. ver == '2' .or. ver == '2.0') then
      raw%version = fmt_v22
    else
      call fail(c, 'unsupported MSH format version '//ver// &
                ' (supported: 4.1 ASCII/binary, 2.2 ASCII; re-export with gmsh -format msh41)')
      return
    end if
    if (ftype /= 0 .and. ftype /= 1) then
      call fail(c, 'invalid file type '//itoa(ftype)//' in $MeshFormat')
      return
    end if
    c%binary = ftype == 1
    if (c%binary .and. raw%version /= fmt_v41) then
      call fail(c, 'binary MSH '//ver//' is not supported (use ASCII, or binary MSH 4.1)')
      return
    end if
    if (c%binary) then
      if (dsize /= 8) then
        call fail(c, 'binary data size '//itoa(dsize)//' is not supported (need 8-byte size_t)')
        return
      end if
      ! The binary marker int 1 follows the header line; anything else means
      ! the file was written on a machine with the other byte order.
      call skip_line(c)
      call rd_int(c, one, 'binary endianness marker')
      if (c%bad) return
      if (one /= 1) then
        call fail(c, 'binary file has foreign byte order (only little-endian files are supported)')
        return
      end if
    end if
  end subroutine parse_format

  !> $PhysicalNames is ASCII even in binary files.
  subroutine parse_names(c, raw)
    type(cursor_t), intent(inout) :: c
    type(raw_t), intent(inout) :: raw
    integer(i8) :: n, d, t, k
    integer :: i

    call get_i8(c, n, 'number of physical names')
    if (c%bad) return
    if (n < 0 .or. n > c%n) then
      call fail(c, 'invalid number of physical names: '//itoa(n))
      return
    end if
    raw%n_names = int(n)
    allocate(raw%name_dim(n), raw%name_tag(n), raw%name_str(n))
    do i = 1, raw%n_names
      call get_i8(c, d, 'physical name dimension')
      call get_i8(c, t, 'physical name tag')
      if (c%bad) return
      if (d < 0 .or. d > 3 .or. abs(t) > huge(1)) then
        call fail(c, 'invalid physical name entry (dim '//itoa(d)//', tag '//itoa(t)//')')
        return
      end if
      raw%name_dim(i) = int(d)
      raw%name_tag(i) = int(abs(t))
      call skip_ws(c)
      if (c%pos > c%n) then
        call fail_eof(c, 'physical names')
        return
      end if
      if (c%buf(c%pos:c%pos) /= '"') then
        call fail(c, 'physical name of group '//itoa(t)//' is not quoted')
        return
      end if
      ! the name ends at the next quote; it may contain blanks
      k = scan(c%buf(c%pos+1:min(c%n, c%pos+1024)), '"'//achar(10), kind=i8)
      if (k == 0) then
        call fail(c, 'unterminated physical name of group '//itoa(t))
        return
      end if
      if (c%buf(c%pos+k:c%pos+k) /= '"') then
        call fail(c, 'unterminated physical name of group '//itoa(t))
        return
      end if
      if (k - 1 > max_name_len) then
        call fail(c, 'physical name "'//c%buf(c%pos+1:c%pos+k-1)//'" is longer than '// &
                  itoa(max_name_len)//' characters')
        return
      end if
      raw%name_str(i) = c%buf(c%pos+1:c%pos+k-1)
      c%pos = c%pos + k + 1
    end do
  end subroutine parse_names

  ! ==========================================================================
  !  MSH 4.1 sections
  ! ==========================================================================

  subroutine parse_entities(c, raw)
    type(cursor_t), intent(inout) :: c
    type(raw_t), intent(inout) :: raw
    integer(i8) :: cnt(4), np
    integer(i8) :: i
    integer :: k

    do k = 1, 4
      call rd_size(c, cnt(k), 'entity counts')
    end do
    if (c%bad) return
    if (any(cnt > c%n - c%pos + 1)) then
      call fail(c, 'invalid entity counts in $Entities (file corrupt or truncated)')
      return
    end if
    ! points: tag, x, y, z, physical tags (no bounding entities)
    do i = 1, cnt(1)
      call skip_values(c, 1_i8, int_bytes, 'point entity tag')
      call skip_values(c, 3_i8, real_bytes, 'point entity coordinates')
      call rd_size(c, np, 'number of physical tags')
      if (c%bad) return
      call skip_values(c, np, int_bytes, 'point entity physical tags')
    end do
    do k = 1, 3
      call read_entity_list(c, cnt(k+1), raw%ents(k))
    end do
  end subroutine parse_entities

  !> Curves, surfaces or volumes: tag, bounding box, physical tags, bounding entities.
  subroutine read_entity_list(c, cnt, list)
    type(cursor_t), intent(inout) :: c
    integer(i8), intent(in) :: cnt
    type(entity_list_t), intent(inout) :: list
    integer(i8) :: np, nb, j
    integer :: i, m, ph

    if (c%bad) return
    list%n = int(cnt)
    allocate(list%tag(list%n), list%first(list%n+1), list%phys(max(16, list%n)))
    m = 0
    do i = 1, list%n
      call rd_int(c, list%tag(i), 'entity tag')
      call skip_values(c, 6_i8, real_bytes, 'entity bounding box')
      call rd_size(c, np, 'number of physical tags')
      if (c%bad) return
      if (np > c%n - c%pos + 1) then
        call fail(c, 'invalid number of physical tags in $Entities')
        return
      end if
      list%first(i) = m + 1
      do j = 1, np
        call rd_int(c, ph, 'physical tag')
        if (c%bad) return
        ! gmsh may store a negative tag for a reversed orientation: the group is the same
        if (ph /= 0) then
          if (m == size(list%phys)) call grow_int(list%phys, 2*m)
          m = m + 1
          list%phys(m) = abs(ph)
        end if
      end do
      call rd_size(c, nb, 'number of bounding entities')
      call skip_values(c, nb, int_bytes, 'bounding entity tags')
      if (c%bad) return
    end do
    list%first(list%n+1) = m + 1
    allocate(list%skey(list%n), list%sidx(list%n))
    list%skey = int(list%tag, i8)
    call sort_perm(list%skey, list%sidx)
    list%skey = list%skey(list%sidx)
  end subroutine read_entity_list

  subroutine parse_nodes_41(c, raw)
    type(cursor_t), intent(inout) :: c
    type(raw_t), intent(inout) :: raw
    integer(i8) :: nblocks, nnodes, nb, b, k, i
    integer :: edim, etag, param, extra, j

    call rd_counts(c, 'node', nblocks, nnodes)
    if (c%bad) return
    if (nnodes > c%n - c%pos + 1 .or. nnodes > huge(1) .or. nblocks > c%n - c%pos + 1) then
      call fail(c, 'invalid node count '//itoa(nnodes)//' in $Nodes (file corrupt or truncated)')
      return
    end if
    raw%nn = int(nnodes)
    allocate(raw%ntag(raw%nn), raw%nx(3, raw%nn))
    k = 0
    do b = 1, nblocks
      call rd_block_head(c, 'node', 'node block parametric flag', edim, etag, param, nb)
      if (c%bad) return
      if (edim < 0 .or. edim > 3 .or. param < 0 .or. param > 1) then
        call fail(c, 'invalid node block header (entity dim '//itoa(edim)//', parametric '// &
                  itoa(param)//')')
        return
      end if
      if (nb > nnodes - k) then
        call fail(c, 'node blocks hold more nodes than the '//itoa(nnodes)//' declared')
        return
      end if
      ! all tags of the block come first, then all coordinates
      call rd_tags(c, raw%ntag(k+1:k+nb), 'node tag')
      extra = 0
      if (param == 1) extra = edim   ! parametric coordinates u, v, w follow x y z
      do i = k + 1, k + nb
        do j = 1, 3
          call rd_real(c, raw%nx(j, i), 'node coordinate')
        end do
        if (extra > 0) call skip_values(c, int(extra, i8), real_bytes, 'parametric node coordinate')
      end do
      if (c%bad) return
      k = k + nb
    end do
    if (k /= nnodes) then
      call fail(c, 'node blocks hold '//itoa(k)//' nodes but '//itoa(nnodes)//' were declared')
    end if
  end subroutine parse_nodes_41

  subroutine parse_elements_41(c, raw)
    type(cursor_t), intent(inout) :: c
    type(raw_t), intent(inout) :: raw
    integer(i8) :: nblocks, nelem, nb, b, i
    integer :: edim, etag, etype, nn, tdim, i1, k

    call rd_counts(c, 'element', nblocks, nelem)
    if (c%bad) return
    if (nelem > c%n - c%pos + 1 .or. nblocks > c%n - c%pos + 1) then
      call fail(c, 'invalid element count '//itoa(nelem)//' in $Elements (file corrupt or truncated)')
      return
    end if
    do b = 1, nblocks
      call rd_block_head(c, 'element', 'element type', edim, etag, etype, nb)
      if (c%bad) return
      if (nb > c%n - c%pos + 1) then
        call fail(c, 'invalid element block size '//itoa(nb)//' (file corrupt or truncated)')
        return
      end if
      call element_info(etype, nn, tdim)
      k = element_fate(etype, tdim, edim, raw%dim)
      if (k > 0) then
        call read_block(raw%elems(k))
      else if (k < 0 .and. nb > 0) then
        call rd_tag(c, i1, 'element tag')
        if (.not. c%bad) call fail(c, bad_element_text(i1, etype, tdim, edim, raw%dim))
      else
        ! points and other lower-dimensional elements: not needed
        if (nn > 0) then
          call skip_values(c, nb * (1 + nn), size_bytes, 'element data')
        else if (.not. c%binary) then
          ! unknown type in ASCII: one element per line
          call skip_line(c)
          do i = 1, nb
            call skip_line(c)
          end do
        else
          call fail(c, 'unknown element type '//itoa(etype)//' in binary file (cannot skip it)')
        end if
      end if
      if (c%bad) return
    end do

  contains

    !> The nb elements of this block: each a tag and list%nv node tags.
    subroutine read_block(list)
      type(elem_list_t), intent(inout) :: list
      integer(i8) :: e
      call reserve(list, list%n + nb)
      do e = 1, nb
        list%n = list%n + 1
        call rd_tag(c, list%tag(list%n), 'element tag')
        call rd_tags(c, list%node(:, list%n), 'element node tag')
        list%ref(list%n) = etag
      end do
    end subroutine read_block

  end subroutine parse_elements_41

  ! ==========================================================================
  !  MSH 2.2 sections (ASCII only)
  ! ==========================================================================

  subroutine parse_nodes_22(c, raw)
    type(cursor_t), intent(inout) :: c
    type(raw_t), intent(inout) :: raw
    integer(i8) :: nnodes
    integer :: i, j

    call get_i8(c, nnodes, 'number of nodes')
    if (c%bad) return
    if (nnodes < 0 .or. nnodes > c%n - c%pos + 1 .or. nnodes > huge(1)) then
      call fail(c, 'invalid node count '//itoa(nnodes)//' in $Nodes (file corrupt or truncated)')
      return
    end if
    raw%nn = int(nnodes)
    allocate(raw%ntag(raw%nn), raw%nx(3, raw%nn))
    do i = 1, raw%nn
      call rd_tag(c, raw%ntag(i), 'node tag')
      do j = 1, 3
        call get_real(c, raw%nx(j, i), 'node coordinate')
      end do
      if (c%bad) return
    end do
  end subroutine parse_nodes_22

  !> Each line: tag type ntags tag1..tagN node1..nodeM.  The first tag is the
  !> physical group; an element in several groups is written once per group.
  subroutine parse_elements_22(c, raw)
    type(cursor_t), intent(inout) :: c
    type(raw_t), intent(inout) :: raw
    integer(i8) :: nelem, i
    integer :: etag, etype, ntags, phys, v, j, nn, tdim, k

    call get_i8(c, nelem, 'number of elements')
    if (c%bad) return
    if (nelem < 0 .or. nelem > c%n - c%pos + 1) then
      call fail(c, 'invalid element count '//itoa(nelem)//' in $Elements (file corrupt or truncated)')
      return
    end if
    do i = 1, nelem
      call rd_tag(c, etag, 'element tag')
      call rd_int(c, etype, 'element type')
      call rd_int(c, ntags, 'number of element tags')
      if (c%bad) return
      if (ntags < 0 .or. ntags > 1000) then
        call fail(c, 'element '//itoa(etag)//': invalid number of tags '//itoa(ntags))
        return
      end if
      phys = 0
      do j = 1, ntags
        call rd_int(c, v, 'element tag list')
        if (j == 1) phys = abs(v)
      end do
      if (c%bad) return
      call element_info(etype, nn, tdim)
      k = element_fate(etype, tdim, tdim, raw%dim)
      if (k > 0) then
        call add_element(raw%elems(k))
      else if (k < 0) then
        call fail(c, bad_element_text(etag, etype, tdim, tdim, raw%dim))
        return
      else
        if (phys /= 0 .and. tdim == raw%dim - 1) then
          if (.not. allocated(raw%keys)) allocate(raw%keys(16))
          if (raw%n_keys == 0) then
            call push_key(raw%keys, raw%n_keys, tdim, phys)
          else if (raw%keys(raw%n_keys) /= tdim * dim_shift + phys) then
            call push_key(raw%keys, raw%n_keys, tdim, phys)
          end if
        end if
        call skip_line(c)      ! one element per line
      end if
      if (c%bad) return
    end do

  contains

    !> This element (tag etag, node tags to read), kept only if it is in a
    !> physical group.
    subroutine add_element(list)
      type(elem_list_t), intent(inout) :: list
      if (list%n == size_or_zero(list%tag)) call reserve(list, max(1024_i8, 2_i8 * list%n))
      list%n = list%n + 1
      list%tag(list%n) = etag
      list%ref(list%n) = phys
      call rd_tags(c, list%node(:, list%n), 'element node tag')
      if (phys == 0) list%n = list%n - 1    ! not in a physical group: drop
    end subroutine add_element

  end subroutine parse_elements_22

  ! ==========================================================================
  !  Building the mesh from the raw data
  ! ==========================================================================

  !> The mesh of dimension raw%dim: its cells are the elements of
  !> raw%elems(dim) in physical groups of that dimension, its facets those of
  !> raw%elems(dim-1) in physical groups of dimension dim-1.
  subroutine build_mesh(raw, scale, mesh, msg)
    type(raw_t), intent(inout) :: raw
    real(rk), intent(in) :: scale
    type(gmsh_mesh_t), intent(inout) :: mesh
    character(len=:), allocatable, intent(out) :: msg

    integer(i8), allocatable :: gkey(:), key(:)
    integer, allocatable :: perm(:), keep(:), kgrp(:), rows(:), rgrp(:), map(:), ttag(:)
    integer, allocatable :: hkey(:), hval(:)
    integer :: hbits
    integer :: i, j, k, m, ng, e, phys, g, nkeep, nbad, nrows, dim, kf
    integer :: last_ref, last_g
    integer(i8) :: tmin, tmax
    real(rk) :: extent
    logical :: dense
    character(len=:), allocatable :: tags

    msg = ''
    dim = raw%dim
    kf = dim - 1                ! the facets' dimension
    ! an element tag names one element: two different elements under one tag
    ! would be merged into one below (the later one lost)
    call duplicate_tags(raw, msg)
    if (len(msg) > 0) return
    ! a MSH 4.1 file without $Entities simply has no physical groups
    do k = 1, 3
      call init_entities(raw%ents(k))
    end do

    ! ---- physical groups: named ones plus every referenced tag (dims kf, dim)
    allocate(key(raw%n_names + 16))
    m = 0
    do i = 1, raw%n_names
      if (raw%name_dim(i) >= kf .and. raw%name_dim(i) <= dim) &
        call push_key(key, m, raw%name_dim(i), raw%name_tag(i))
    end do
    do k = kf, dim
      if (raw%version == fmt_v41) then
        do i = 1, raw%ents(k)%first(raw%ents(k)%n+1) - 1
          call push_key(key, m, k, raw%ents(k)%phys(i))
        end do
      else
        call push_refs(raw%elems(k), k)
      end if
    end do
    do i = 1, raw%n_keys       ! (MSH 2.2 only)
      call push_key(key, m, int(raw%keys(i) / dim_shift), int(mod(raw%keys(i), dim_shift)))
    end do
    allocate(perm(m))
    call sort_unique(key(1:m), perm, ng)
    allocate(gkey(ng))
    gkey = key(perm(1:ng))
    deallocate(key, perm)
    mesh%n_groups = ng
    allocate(mesh%groups(ng))
    do g = 1, ng
      mesh%groups(g)%dim = int(gkey(g) / dim_shift)
      mesh%groups(g)%tag = int(mod(gkey(g), dim_shift))
      mesh%groups(g)%name = 'group_'//itoa(mesh%groups(g)%tag)
      do i = 1, raw%n_names    ! first matching name wins
        if (raw%name_dim(i) == mesh%groups(g)%dim .and. raw%name_tag(i) == mesh%groups(g)%tag) then
          mesh%groups(g)%name = raw%name_str(i)
          exit
        end if
      end do
    end do
    if (count(mesh%groups(:)%dim == dim) == 0) then
      msg = 'no physical '//trim(entity_name(dim))//' group: define one ("'// &
            trim(physical_cmd(dim))//'") so the solver knows which '// &
            trim(simplex_plural(dim)(8:))//' form the body'
      return
    end if

    ! ---- cells in a physical group of dimension dim: first physical tag wins
    allocate(keep(raw%elems(dim)%n), kgrp(raw%elems(dim)%n))
    nkeep = 0
    last_ref = -1
    last_g = 0
    do i = 1, raw%elems(dim)%n
      if (raw%elems(dim)%ref(i) /= last_ref) then    ! blocks share a ref: look up once per run
        last_ref = raw%elems(dim)%ref(i)
        phys = 0
        if (raw%version == fmt_v41) then
          e = find_entity(raw%ents(dim), last_ref)
          if (e > 0) then
            if (raw%ents(dim)%first(e+1) > raw%ents(dim)%first(e)) &
              phys = raw%ents(dim)%phys(raw%ents(dim)%first(e))
          end if
        else
          phys = last_ref
        end if
        last_g = 0
        if (phys > 0) last_g = find_sorted(gkey(1:ng), dim * dim_shift + phys)
      end if
      if (last_g > 0) then
        nkeep = nkeep + 1
        keep(nkeep) = i
        kgrp(nkeep) = last_g
      end if
    end do
    if (nkeep == 0) then
      msg = 'no '//trim(simplex_plural(dim))//' belong to a physical '//trim(entity_name(dim))// &
            ' group (note: MSH 2.2 written with Mesh.SaveAll = 1 carries no physical tags)'
      return
    end if
    ! stable sort by element tag; duplicates (MSH 2.2 lists an element once
    ! per physical group) keep their first occurrence
    allocate(key(nkeep), perm(nkeep))
    key = int(raw%elems(dim)%tag(keep(1:nkeep)), i8)
    call sort_unique(key, perm, m)
    mesh%n_cells = m
    allocate(mesh%cell_tag(m), mesh%cell(m, dim+1), mesh%cell_group(m))
    do i = 1, m
      mesh%cell_tag(i) = raw%elems(dim)%tag(keep(perm(i)))
      mesh%cell_group(i) = kgrp(perm(i))
      mesh%cell(i, :) = raw%elems(dim)%node(:, keep(perm(i)))   ! node tags for now
    end do
    deallocate(key, perm, keep, kgrp, raw%elems(dim)%tag, raw%elems(dim)%ref, raw%elems(dim)%node)

    ! ---- facets: one row per (facet, physical group of dimension kf)
    nrows = 0
    call facet_rows(.false.)      ! count
    allocate(rows(nrows), rgrp(nrows))
    nrows = 0
    call facet_rows(.true.)       ! fill
    ! order by (element tag, group); drop exact duplicates
    allocate(key(nrows), perm(nrows))
    do i = 1, nrows
      key(i) = int(raw%elems(kf)%tag(rows(i)), i8) * int(ng + 1, i8) + rgrp(i)
    end do
    call sort_unique(key, perm, m)
    mesh%n_facets = m
    allocate(mesh%facet(m, dim), mesh%facet_group(m), ttag(m))
    do i = 1, m
      ttag(i) = raw%elems(kf)%tag(rows(perm(i)))     ! kept only for error messages
      mesh%facet(i, :) = raw%elems(kf)%node(:, rows(perm(i)))
      mesh%facet_group(i) = rgrp(perm(i))
    end do
    deallocate(key, perm, rows, rgrp)

    ! ---- nodes sorted by tag
    if (raw%nn == 0) then
      msg = 'the mesh has no nodes'
      return
    end if
    mesh%n_nodes = raw%nn
    allocate(key(raw%nn), perm(raw%nn))
    key = int(raw%ntag, i8)
    call sort_perm(key, perm)
    allocate(mesh%node_tag(raw%nn), mesh%x(raw%nn, 3))
    do i = 1, raw%nn
      mesh%node_tag(i) = raw%ntag(perm(i))
      if (i > 1) then
        if (mesh%node_tag(i) == mesh%node_tag(i-1)) then
          msg = 'duplicate node tag '//itoa(mesh%node_tag(i))
          return
        end if
      end if
      ! volumes are cubes of lengths: beyond max_coord they overflow and
      ! every tetrahedron would look degenerate (tested before the product,
      ! which could overflow: debug builds trap that)
      if (.not. all(ieee_is_finite(raw%nx(:, perm(i))) .and. &
                    abs(raw%nx(:, perm(i))) <= max_coord / max(scale, 1.0e-270_rk))) then
        msg = 'node '//itoa(mesh%node_tag(i))//' has coordinates out of range: ('// &
              r2s(raw%nx(1, perm(i)))//', '//r2s(raw%nx(2, perm(i)))//', '//r2s(raw%nx(3, perm(i)))// &
              ') in the file, times &mesh scale = '//r2s(scale)//', must be finite and at most '// &
              r2s(max_coord)//' m in magnitude'
        return
      end if
      mesh%x(i, :) = raw%nx(:, perm(i)) * scale
    end do
    ! a 2D mesh lies in the plane z = 0 (up to rounding, relative to its size)
    if (dim == 2) then
      extent = 0.0_rk
      do j = 1, 3
        extent = max(extent, maxval(raw%nx(j, :)) - minval(raw%nx(j, :)))
      end do
      do i = 1, raw%nn
        if (abs(raw%nx(3, perm(i))) > degenerate_tol * extent) then
          msg = 'node '//itoa(mesh%node_tag(i))//' has z = '//r2s(raw%nx(3, perm(i)))// &
                ' in the file, but a 2D mesh must lie in the plane z = 0: draw the geometry '// &
                'in the (x, y) plane (axisymmetric: x radial, y along the axis)'
          return
        end if
      end do
      ! within rounding of the plane: on it (the solver's 2D state keeps z = 0)
      mesh%x(:, 3) = 0.0_rk
    end if
    deallocate(key, perm, raw%ntag, raw%nx)

    ! ---- node tag -> index: direct table when tags are dense enough,
    ! hash table otherwise (O(1) per lookup either way)
    tmin = mesh%node_tag(1)
    tmax = mesh%node_tag(raw%nn)
    dense = tmax - tmin + 1 <= 4_i8 * raw%nn + 1024_i8
    if (dense) then
      allocate(map(tmin:tmax))
      map = 0
      do i = 1, raw%nn
        map(mesh%node_tag(i)) = i
      end do
    else
      call hash_build(mesh%node_tag, hkey, hval, hbits)
    end if
    nbad = 0
    do i = 1, mesh%n_cells
      do j = 1, dim + 1
        call translate(mesh%cell(i, j), mesh%cell_tag(i))
      end do
    end do
    do i = 1, mesh%n_facets
      do j = 1, dim
        call translate(mesh%facet(i, j), ttag(i))
      end do
    end do
    if (nbad > 0) return

    ! ---- orientation and degeneracy
    call orient_cells(mesh, nbad, tags)
    if (nbad > 0) then
      msg = itoa(nbad)//' degenerate (zero-'//trim(measure_name(dim))//') '// &
            trim(simplex_plural(dim)(8:))//achar(10)//'  element tags: '//tags
      return
    end if

  contains

    !> MSH 2.2: the physical groups (of dimension kd) the elements refer to.
    subroutine push_refs(list, kd)
      type(elem_list_t), intent(in) :: list
      integer, intent(in) :: kd
      integer :: ir, last
      last = -1
      do ir = 1, list%n
        if (list%ref(ir) /= last) call push_key(key, m, kd, list%ref(ir))
        last = list%ref(ir)
      end do
    end subroutine push_refs

    subroutine facet_rows(fill)
      logical, intent(in) :: fill
      integer :: ir, jp, ie
      do ir = 1, raw%elems(kf)%n
        if (raw%version == fmt_v41) then
          ie = find_entity(raw%ents(kf), raw%elems(kf)%ref(ir))
          if (ie == 0) cycle
          do jp = raw%ents(kf)%first(ie), raw%ents(kf)%first(ie+1) - 1
            call facet_row(ir, raw%ents(kf)%phys(jp), fill)
          end do
        else
          call facet_row(ir, raw%elems(kf)%ref(ir), fill)
        end if
      end do
    end subroutine facet_rows

    !> The row of facet ir in physical group phys (only counted unless fill).
    subroutine facet_row(ir, phys, fill)
      integer, intent(in) :: ir, phys
      logical, intent(in) :: fill
      nrows = nrows + 1
      if (fill) then
        rows(nrows) = ir
        rgrp(nrows) = find_sorted(gkey(1:ng), kf * dim_shift + phys)
      end if
    end subroutine facet_row

    !> Replace a node tag by its index; record the first failure.
    subroutine translate(v, etag)
      integer, intent(inout) :: v
      integer, intent(in) :: etag
      integer :: idx
      idx = 0
      if (dense) then
        if (v >= tmin .and. v <= tmax) idx = map(v)
      else
        idx = hash_find(hkey, hval, hbits, v)
      end if
      if (idx == 0) then
        nbad = nbad + 1
        if (nbad == 1) msg = 'element '//itoa(etag)//' references unknown node tag '//itoa(v)
      end if
      v = idx
    end subroutine translate

  end subroutine build_mesh

  !> What becomes of elements of gmsh type etype (of dimension tdim, from
  !> element_info) in a block of entity dimension edim (MSH 2.2: edim = tdim)
  !> when a mesh of dimension dim is read: kept in raw%elems(k) (k > 0: the
  !> linear simplices of dimensions dim-1 and dim), skipped (0: points and
  !> other lower-dimensional elements) or refused (-1: any other element of
  !> dimension dim or more, or a type gmsh does not have: skipping it would
  !> lose part of the body without a word).
  pure integer function element_fate(etype, tdim, edim, dim) result(k)
    integer, intent(in) :: etype, tdim, edim, dim
    integer :: j
    do j = dim - 1, dim
      if (etype == linear_type(j) .and. edim == j) then
        k = j
        return
      end if
    end do
    k = 0
    if (tdim < 0 .or. tdim >= dim .or. edim >= dim) k = -1
  end function element_fate

  !> The message for an element udar cannot use in a mesh of dimension dim
  !> (tdim < 0: unknown type; edim: dimension of its block, = tdim in MSH 2.2).
  function bad_element_text(etag, etype, tdim, edim, dim) result(msg)
    integer, intent(in) :: etag, etype, tdim, edim, dim
    character(len=:), allocatable :: msg
    character(len=:), allocatable :: what
    logical :: high_order
    character(len=*), parameter :: lower_blocks(2:3) = [character(len=22) :: &
         'line or point', 'surface or line']
    if (tdim < 0) then
      msg = 'element '//itoa(etag)//' has element type '//itoa(etype)//', which udar does not '// &
            'know: not a gmsh type (file damaged?) or a high-order one (mesh with gmsh -'// &
            itoa(dim)//' -order 1)'
      return
    end if
    select case (etype)
    case (3)
      what = 'a 4-node quadrilateral'
    case (5)
      what = 'an 8-node hexahedron'
    case (6)
      what = 'a 6-node prism'
    case (7)
      what = 'a 5-node pyramid'
    case (9)
      what = 'a 6-node (second-order) triangle'
    case (10)
      what = 'a 9-node (second-order) quadrilateral'
    case (11)
      what = 'a 10-node (second-order) tetrahedron'
    case (16)
      what = 'an 8-node (second-order) quadrilateral'
    case (20:25)
      what = 'a higher-order triangle'
    case (29:31, 71:75)
      what = 'a higher-order tetrahedron'
    case (12, 17, 92:98)
      what = 'a higher-order hexahedron'
    case (13, 18, 106:110)
      what = 'a higher-order prism'
    case (14, 19, 118:124)
      what = 'a higher-order pyramid'
    case default
      what = 'a volume element'
      if (tdim < 3) what = 'a '//itoa(tdim)//'D element'
      if (tdim >= 1) then
        if (etype == linear_type(tdim)) what = 'a '//trim(simplex_name(tdim))
      end if
    end select
    ! MSH 4.1: a block of another dimension than its elements'
    if (edim > tdim) then
      what = 'a '//itoa(tdim)//'D element in a block of '//trim(entity_name(min(edim, 3)))//' elements'
    else if (edim < tdim .and. tdim >= 2 .and. etype == linear_type(tdim)) then
      what = 'a '//trim(simplex_name(tdim))//' in a block of '//trim(lower_blocks(tdim))//' elements'
    end if
    msg = 'element '//itoa(etag)//' is '//what//' (gmsh type '//itoa(etype)//'): '
    if (dim == 2 .and. max(tdim, edim) == 3) then
      msg = msg//'the mesh is 3D but a 2D calculation was asked for; mesh the geometry in '// &
            '2D (gmsh -2) with 3-node triangles in physical surfaces, or run the calculation in 3D'
      return
    end if
    msg = msg//'udar takes only '//trim(simplex_plural(dim))//' (type '//itoa(linear_type(dim))// &
          ') as '//trim(entity_name(dim))//' elements'
    if (dim == 2) msg = msg//' in 2D'
    select case (etype)
    case (11, 29:31, 71:75)
      high_order = dim == 3
    case (9, 20:25)
      high_order = dim == 2
    case default
      high_order = .false.
    end select
    if (high_order) then
      msg = msg//'; mesh with first-order elements: gmsh -'//itoa(dim)//' -order 1 (Mesh.ElementOrder = 1)'
    else if (dim == 3) then
      msg = msg//'; mesh the volumes with tetrahedra only (no Recombine, no extrusion Layers, '// &
            'no Mesh.SubdivisionAlgorithm)'
    else
      msg = msg//'; mesh the surfaces with triangles only (no Recombine, no Mesh.RecombineAll, '// &
            'no Mesh.SubdivisionAlgorithm)'
    end if
  end function bad_element_text

  !> First duplicate element tag among the kept elements (tets, triangles,
  !> lines), as a message ('' if none). MSH 2.2 writes an element once per
  !> physical group: the same tag with the same nodes is that, not a duplicate.
  subroutine duplicate_tags(raw, msg)
    type(raw_t), intent(in) :: raw
    character(len=:), allocatable, intent(inout) :: msg
    integer(i8), allocatable :: key(:)
    integer, allocatable :: perm(:)
    integer :: first(3), n, i, k, ka, kb, a, b
    logical :: same

    ! tets first, then triangles, then lines: key position p is element
    ! p - first(k) of the list k holding it
    n = 0
    do k = 3, 1, -1
      first(k) = n
      n = n + raw%elems(k)%n
    end do
    if (n < 2) return
    allocate(key(n), perm(n))
    do k = 1, 3
      if (raw%elems(k)%n > 0) key(first(k)+1:first(k)+raw%elems(k)%n) = raw%elems(k)%tag(1:raw%elems(k)%n)
    end do
    call sort_perm(key, perm)
    do i = 2, n
      if (key(perm(i)) /= key(perm(i-1))) cycle
      call locate(perm(i-1), ka, a)
      call locate(perm(i), kb, b)
      same = ka == kb
      if (same) same = all(raw%elems(ka)%node(:, a) == raw%elems(kb)%node(:, b))
      if (same .and. raw%version == fmt_v22) cycle
      msg = 'element tag '//itoa(int(key(perm(i))))//' is used by '//elem_text(ka, a)//' and by '// &
            elem_text(kb, b)//': element tags must be unique (file damaged or concatenated?)'
      return
    end do

  contains

    subroutine locate(p, kl, j)
      integer, intent(in) :: p
      integer, intent(out) :: kl, j
      do kl = 1, 3
        if (p > first(kl) .and. p <= first(kl) + raw%elems(kl)%n) exit
      end do
      j = p - first(kl)
    end subroutine locate

    function elem_text(kl, j) result(t)
      integer, intent(in) :: kl, j
      character(len=:), allocatable :: t
      integer :: m
      t = 'a '//trim(simplex_name(kl))//' (nodes'
      do m = 1, raw%elems(kl)%nv
        t = t//' '//itoa(raw%elems(kl)%node(m, j))
      end do
      t = t//')'
    end function elem_text

  end subroutine duplicate_tags

  !> Make every cell positively oriented (swap nodes 2 and 3) and collect
  !> degenerate ones.  Tets: signed 6V, positive for a right-handed
  !> (2-1, 3-1, 4-1); triangles: twice the signed area in the (x, y) plane,
  !> positive counter-clockwise.  Degenerate: |measure| <= tol * L**dim with L
  !> the longest edge, which is independent of the length unit.
  subroutine orient_cells(mesh, nbad, tags)
    type(gmsh_mesh_t), intent(inout) :: mesh
    integer, intent(out) :: nbad
    character(len=:), allocatable, intent(out) :: tags
    real(rk) :: p(3, 4), a(3), b(3), d(3), v, l2, lsize
    integer :: i, j, k, t, nv

    nbad = 0
    tags = ''
    nv = mesh%dim + 1
    do i = 1, mesh%n_cells
      do k = 1, nv
        p(:, k) = mesh%x(mesh%cell(i, k), :)
      end do
      a = p(:, 2) - p(:, 1)
      b = p(:, 3) - p(:, 1)
      l2 = 0.0_rk
      do k = 1, nv - 1
        do j = k + 1, nv
          l2 = max(l2, sum((p(:, j) - p(:, k))**2))
        end do
      end do
      if (mesh%dim == 3) then
        d = p(:, 4) - p(:, 1)
        v = a(1) * (b(2) * d(3) - b(3) * d(2)) - a(2) * (b(1) * d(3) - b(3) * d(1)) &
          + a(3) * (b(1) * d(2) - b(2) * d(1))
        lsize = l2 * sqrt(l2)
      else
        v = a(1) * b(2) - b(1) * a(2)
        lsize = l2
      end if
      if (abs(v) <= degenerate_tol * lsize) then
        nbad = nbad + 1
        if (nbad <= max_listed) tags = tags//' '//itoa(mesh%cell_tag(i))
      else if (v < 0.0_rk) then
        t = mesh%cell(i, 2)
        mesh%cell(i, 2) = mesh%cell(i, 3)
        mesh%cell(i, 3) = t
        mesh%n_inverted = mesh%n_inverted + 1
      end if
    end do
    if (nbad > max_listed) tags = tags//' and '//itoa(nbad - max_listed)//' more'
    if (nbad > 0) tags = tags(2:)     ! drop the leading blank
  end subroutine orient_cells

  ! ==========================================================================
  !  Cursor primitives
  ! ==========================================================================

  !> Keep the first error only: later ones are consequences of it.
  subroutine fail(c, msg)
    type(cursor_t), intent(inout) :: c
    character(len=*), intent(in) :: msg
    if (c%bad) return
    c%bad = .true.
    c%msg = msg
  end subroutine fail

  subroutine fail_eof(c, what)
    type(cursor_t), intent(inout) :: c
    character(len=*), intent(in) :: what
    call fail(c, 'unexpected end of file while reading '//what//' (file truncated?)')
  end subroutine fail_eof

  subroutine skip_ws(c)
    type(cursor_t), intent(inout) :: c
    do while (c%pos <= c%n)
      if (iachar(c%buf(c%pos:c%pos)) > 32) exit
      c%pos = c%pos + 1
    end do
  end subroutine skip_ws

  !> Move past the next line feed.
  subroutine skip_line(c)
    type(cursor_t), intent(inout) :: c
    integer(i8) :: k
    if (c%pos > c%n) return
    k = index(c%buf(c%pos:c%n), achar(10), kind=i8)
    if (k == 0) then
      c%pos = c%n + 1
    else
      c%pos = c%pos + k
    end if
  end subroutine skip_line

  !> Move to the start of the next token; reaching the end of the file
  !> instead is an error (nothing is done after an earlier one).
  subroutine seek_token(c, what)
    type(cursor_t), intent(inout) :: c
    character(len=*), intent(in) :: what
    if (c%bad) return
    call skip_ws(c)
    if (c%pos > c%n) call fail_eof(c, what)
  end subroutine seek_token

  !> Position after the token that starts at p (at the next blank or control
  !> character, or past the end).
  pure integer(i8) function token_end(c, p) result(q)
    type(cursor_t), intent(in) :: c
    integer(i8), intent(in) :: p
    q = p
    do while (q <= c%n)
      if (iachar(c%buf(q:q)) <= 32) exit
      q = q + 1
    end do
  end function token_end

  subroutine skip_token(c, what)
    type(cursor_t), intent(inout) :: c
    character(len=*), intent(in) :: what
    call seek_token(c, what)
    if (c%bad) return
    c%pos = token_end(c, c%pos)
  end subroutine skip_token

  !> The whitespace-delimited text at p (at most 40 characters), for messages.
  function token_at(c, p) result(s)
    type(cursor_t), intent(in) :: c
    integer(i8), intent(in) :: p
    character(len=:), allocatable :: s
    s = c%buf(p:min(token_end(c, p), p + 40)-1)
    if (len(s) == 0) s = '<blank>'
  end function token_at

  !> ASCII integer token.
  subroutine get_i8(c, v, what)
    type(cursor_t), intent(inout) :: c
    integer(i8), intent(out) :: v
    character(len=*), intent(in) :: what
    integer(i8) :: p
    integer :: ch, nd
    logical :: neg, ok

    v = 0
    call seek_token(c, what)
    if (c%bad) return
    p = c%pos
    ch = iachar(c%buf(p:p))
    neg = ch == 45
    if (ch == 45 .or. ch == 43) p = p + 1
    nd = 0
    do while (p <= c%n)
      ch = iachar(c%buf(p:p))
      if (ch < 48 .or. ch > 57) exit
      nd = nd + 1
      if (nd > 18) exit
      v = 10 * v + (ch - 48)
      p = p + 1
    end do
    ok = nd > 0 .and. nd <= 18
    if (ok .and. p <= c%n) ok = iachar(c%buf(p:p)) <= 32    ! the digits are the whole token
    if (.not. ok) then
      call fail(c, 'expected an integer ('//what//') but found "'//token_at(c, c%pos)//'"')
      return
    end if
    if (neg) v = -v
    c%pos = p
  end subroutine get_i8

  !> ASCII real token: exact fast path for typical gmsh output (%.16g),
  !> Fortran's own conversion for everything else.
  subroutine get_real(c, x, what)
    type(cursor_t), intent(inout) :: c
    real(rk), intent(out) :: x
    character(len=*), intent(in) :: what
    integer(i8) :: p, s, m
    integer :: ch, nd, e10, ex, nex, ios
    logical :: neg, eneg, fast, any_digit

    x = 0.0_rk
    call seek_token(c, what)
    if (c%bad) return
    s = c%pos
    p = s
    fast = .true.
    any_digit = .false.
    m = 0
    nd = 0
    e10 = 0
    ch = iachar(c%buf(p:p))
    neg = ch == 45
    if (ch == 45 .or. ch == 43) p = p + 1
    call add_digits(.false.)     ! integer part
    if (p <= c%n) then
      if (c%buf(p:p) == '.') then
        p = p + 1
        call add_digits(.true.)  ! fraction
      end if
    end if
    ! exponent
    if (p <= c%n .and. any_digit) then
      if (scan(c%buf(p:p), 'eEdD') > 0) then
        p = p + 1
        eneg = .false.
        if (p <= c%n) then
          eneg = c%buf(p:p) == '-'
          if (c%buf(p:p) == '-' .or. c%buf(p:p) == '+') p = p + 1
        end if
        ex = 0
        nex = 0
        do while (p <= c%n)
          ch = iachar(c%buf(p:p))
          if (ch < 48 .or. ch > 57) exit
          nex = nex + 1
          if (ex < 100000) ex = 10 * ex + (ch - 48)
          p = p + 1
        end do
        if (nex == 0) fast = .false.
        if (eneg) ex = -ex
        e10 = e10 + ex
      end if
    end if
    if (p <= c%n) then
      if (iachar(c%buf(p:p)) > 32) fast = .false.   ! something unusual: nan, inf...
    end if
    if (.not. any_digit) fast = .false.

    if (fast .and. m == 0) then
      x = 0.0_rk
    else if (fast .and. m <= two53 .and. abs(e10) <= 22) then
      x = real(m, rk)
      if (e10 >= 0) then
        x = x * p10(e10)
      else
        x = x / p10(-e10)
      end if
    else
      ! slow but exact general conversion
      p = token_end(c, s)
      read(c%buf(s:p-1), *, iostat=ios) x
      if (ios /= 0) then
        call fail(c, 'expected a real number ('//what//') but found "'//token_at(c, s)//'"')
        return
      end if
      c%pos = p
      return
    end if
    if (neg) x = -x
    c%pos = p

  contains

    !> The run of decimal digits at p.
    subroutine add_digits(frac)
      logical, intent(in) :: frac
      do while (p <= c%n)
        ch = iachar(c%buf(p:p))
        if (ch < 48 .or. ch > 57) exit
        any_digit = .true.
        call add_digit(ch - 48, frac)
        p = p + 1
      end do
    end subroutine add_digits

    subroutine add_digit(dgt, frac)
      integer, intent(in) :: dgt
      logical, intent(in) :: frac
      if (m == 0 .and. dgt == 0) then
        if (frac) e10 = e10 - 1       ! leading zeros are not significant
        return
      end if
      if (nd >= 18) then             ! more digits than fit exactly: slow path
        fast = .false.
        if (.not. frac) e10 = e10 + 1
        return
      end if
      m = 10 * m + dgt
      nd = nd + 1
      if (frac) e10 = e10 - 1
    end subroutine add_digit

  end subroutine get_real

  ! ---- binary primitives (little-endian, checked against the marker)

  !> Claim the next nbytes of a binary file: p is where they start, 0 after an
  !> earlier error or when the file ends first (an error).
  subroutine bin_take(c, nbytes, what, p)
    type(cursor_t), intent(inout) :: c
    integer(i8), intent(in) :: nbytes
    character(len=*), intent(in) :: what
    integer(i8), intent(out) :: p
    p = 0
    if (c%bad) return
    if (nbytes < 0 .or. nbytes > c%n - c%pos + 1) then
      call fail_eof(c, what)
      return
    end if
    p = c%pos
    c%pos = c%pos + nbytes
  end subroutine bin_take

  ! ---- MSH 4.1 typed reads: ASCII token or binary value by file type

  !> An integer field of nbytes (int_bytes or size_bytes) in a binary file.
  subroutine rd_i8(c, v, nbytes, what)
    type(cursor_t), intent(inout) :: c
    integer(i8), intent(out) :: v
    integer(i8), intent(in) :: nbytes
    character(len=*), intent(in) :: what
    integer(i8) :: p
    if (.not. c%binary) then
      call get_i8(c, v, what)
      return
    end if
    v = 0
    call bin_take(c, nbytes, what, p)
    if (p == 0) return
    if (nbytes == int_bytes) then
      v = transfer(c%buf(p:p+3), 0_int32)
    else
      v = transfer(c%buf(p:p+7), 0_int64)
    end if
  end subroutine rd_i8

  !> size_t count (must be >= 0).
  subroutine rd_size(c, v, what)
    type(cursor_t), intent(inout) :: c
    integer(i8), intent(out) :: v
    character(len=*), intent(in) :: what
    call rd_i8(c, v, size_bytes, what)
    if (v < 0 .and. .not. c%bad) call fail(c, 'negative '//what//': '//itoa(v))
  end subroutine rd_size

  !> int field (entity tags, element types...).
  subroutine rd_int(c, v, what)
    type(cursor_t), intent(inout) :: c
    integer, intent(out) :: v
    character(len=*), intent(in) :: what
    integer(i8) :: w
    call rd_i8(c, w, int_bytes, what)
    v = 0
    if (c%bad) return
    ! (a binary int32 is in range by construction)
    if (.not. c%binary .and. abs(w) > huge(1)) then
      call fail(c, what//' out of range: '//itoa(w))
      return
    end if
    v = int(w)
  end subroutine rd_int

  !> Node or element tag: size_t in the file, positive default integer here.
  subroutine rd_tag(c, v, what)
    type(cursor_t), intent(inout) :: c
    integer, intent(out) :: v
    character(len=*), intent(in) :: what
    integer(i8) :: w
    call rd_i8(c, w, size_bytes, what)
    v = 0
    if (c%bad) return
    if (w < 1 .or. w > huge(1)) then
      call fail(c, 'invalid '//what//' '//itoa(w)//' (must be in 1..'//itoa(huge(1))//')')
      return
    end if
    v = int(w)
  end subroutine rd_tag

  subroutine rd_tags(c, v, what)
    type(cursor_t), intent(inout) :: c
    integer, intent(out) :: v(:)
    character(len=*), intent(in) :: what
    integer :: k
    do k = 1, size(v)
      call rd_tag(c, v(k), what)
    end do
  end subroutine rd_tags

  subroutine rd_real(c, x, what)
    type(cursor_t), intent(inout) :: c
    real(rk), intent(out) :: x
    character(len=*), intent(in) :: what
    integer(i8) :: bits
    if (c%binary) then
      call rd_i8(c, bits, real_bytes, what)    ! the 8 bytes as they are (0 on failure)
      x = transfer(bits, 0.0_rk)
    else
      call get_real(c, x, what)
    end if
  end subroutine rd_real

  !> Head of a MSH 4.1 $Nodes or $Elements section (what: 'node', 'element'):
  !> the numbers of blocks and of entries (the tag range is not needed).
  subroutine rd_counts(c, what, nblocks, n)
    type(cursor_t), intent(inout) :: c
    character(len=*), intent(in) :: what
    integer(i8), intent(out) :: nblocks, n
    integer(i8) :: tag
    call rd_size(c, nblocks, 'number of '//what//' blocks')
    call rd_size(c, n, 'number of '//what//'s')
    call rd_size(c, tag, 'minimum '//what//' tag')
    call rd_size(c, tag, 'maximum '//what//' tag')
  end subroutine rd_counts

  !> Head of one entity block of such a section: entity dimension and tag,
  !> one more int k (the parametric flag of nodes, the element type) and the
  !> number of entries.
  subroutine rd_block_head(c, what, k_what, edim, etag, k, nb)
    type(cursor_t), intent(inout) :: c
    character(len=*), intent(in) :: what, k_what
    integer, intent(out) :: edim, etag, k
    integer(i8), intent(out) :: nb
    call rd_int(c, edim, what//' block entity dimension')
    call rd_int(c, etag, what//' block entity tag')
    call rd_int(c, k, k_what)
    call rd_size(c, nb, 'number of '//what//'s in block')
  end subroutine rd_block_head

  !> Skip k values of nbytes each (binary) or k tokens (ASCII).
  subroutine skip_values(c, k, nbytes, what)
    type(cursor_t), intent(inout) :: c
    integer(i8), intent(in) :: k, nbytes
    character(len=*), intent(in) :: what
    integer(i8) :: i, p
    if (c%bad) return
    if (k < 0 .or. k > c%n) then
      call fail(c, 'invalid count while skipping '//what)
      return
    end if
    if (c%binary) then
      call bin_take(c, k * nbytes, what, p)
    else
      do i = 1, k
        call skip_token(c, what)
        if (c%bad) return
      end do
    end if
  end subroutine skip_values

  ! ==========================================================================
  !  Small utilities
  ! ==========================================================================

  !> Number of nodes and dimension of a gmsh element type (nn = 0: unknown).
  !> Covers the fixed-size types whose numbering is stable across gmsh versions.
  pure subroutine element_info(etype, nn, dim)
    integer, intent(in) :: etype
    integer, intent(out) :: nn, dim
    integer, parameter :: nn_tab(33) = [2, 3, 4, 4, 8, 6, 5, 3, 6, 9, 10, 27, 18, 14, 1, 8, &
         20, 15, 13, 9, 10, 12, 15, 15, 21, 4, 5, 6, 20, 35, 56, 22, 28]
    integer, parameter :: dim_tab(33) = [1, 2, 2, 3, 3, 3, 3, 1, 2, 2, 3, 3, 3, 3, 0, 2, &
         3, 3, 3, 2, 2, 2, 2, 2, 2, 1, 1, 1, 3, 3, 3, 3, 3]
    integer, parameter :: tet_tab(5) = [84, 120, 165, 220, 286]
    integer, parameter :: pri_tab(5) = [126, 196, 288, 405, 550]
    integer, parameter :: pyr_tab(7) = [30, 55, 91, 140, 204, 285, 385]
    nn = 0
    dim = -1
    select case (etype)
    case (1:33)
      nn = nn_tab(etype)
      dim = dim_tab(etype)
    case (71:75)                     ! complete tets of order 6..10
      nn = tet_tab(etype - 70)
      dim = 3
    case (79:83, 99:105, 111:117, 125:131, 136, 139)   ! other 3D types (sizes vary)
      dim = 3
    case (84)
      nn = 1
      dim = 1
    case (85, 86)
      nn = 1
      dim = 2
    case (87:89)
      nn = 1
      dim = 3
    case (90)
      nn = 40
      dim = 3
    case (91)
      nn = 75
      dim = 3
    case (92:98)                     ! complete hexes of order 3..9
      nn = (etype - 92 + 4)**3
      dim = 3
    case (106:110)                   ! complete prisms of order 5..9
      nn = pri_tab(etype - 105)
      dim = 3
    case (118:124)                   ! complete pyramids of order 3..9
      nn = pyr_tab(etype - 117)
      dim = 3
    case (132)
      nn = 1
      dim = 3
    case (137)
      nn = 16
      dim = 3
    end select
  end subroutine element_info

  !> Stable merge sort: perm orders key ascending.  Keys travel with the
  !> permutation so that merging reads memory sequentially (shuffled tags of
  !> millions of elements would otherwise make it cache-bound).
  subroutine sort_perm(key, perm)
    integer(i8), intent(in) :: key(:)
    integer, intent(out) :: perm(:)
    integer, parameter :: run = 32      ! insertion-sorted runs before merging
    integer(i8), allocatable :: k1(:), k2(:), kt(:)
    integer, allocatable :: p1(:), p2(:), pt(:)
    integer(i8) :: kv
    integer :: n, i, j, pv, width, lo, mid, hi, a, b, k

    n = size(key)
    do i = 1, n
      perm(i) = i
    end do
    ! gmsh usually writes tags in order: skip the work then
    do i = 2, n
      if (key(i) < key(i-1)) exit
    end do
    if (i > n) return

    allocate(k1(n), p1(n), k2(n), p2(n))
    k1 = key
    p1 = perm
    do lo = 1, n, run
      hi = min(lo + run - 1, n)
      do i = lo + 1, hi
        kv = k1(i)
        pv = p1(i)
        j = i - 1
        do while (j >= lo)
          if (k1(j) <= kv) exit
          k1(j+1) = k1(j)
          p1(j+1) = p1(j)
          j = j - 1
        end do
        k1(j+1) = kv
        p1(j+1) = pv
      end do
    end do
    width = run
    do while (width < n)
      do lo = 1, n, 2 * width
        mid = min(lo + width - 1, n)
        hi = min(lo + 2 * width - 1, n)
        a = lo
        b = mid + 1
        do k = lo, hi
          if (a > mid) then
            k2(k) = k1(b)
            p2(k) = p1(b)
            b = b + 1
          else if (b > hi) then
            k2(k) = k1(a)
            p2(k) = p1(a)
            a = a + 1
          else if (k1(b) < k1(a)) then
            k2(k) = k1(b)
            p2(k) = p1(b)
            b = b + 1
          else
            k2(k) = k1(a)
            p2(k) = p1(a)
            a = a + 1
          end if
        end do
      end do
      ! the merged arrays become the input of the next pass
      call move_alloc(k1, kt)
      call move_alloc(k2, k1)
      call move_alloc(kt, k2)
      call move_alloc(p1, pt)
      call move_alloc(p2, p1)
      call move_alloc(pt, p2)
      width = 2 * width
    end do
    perm = p1
  end subroutine sort_perm

  !> Open-addressing hash table of positive, distinct tags -> position.
  !> Size is a power of two >= 2n, so probe chains stay short.
  subroutine hash_build(tags, hkey, hval, bits)
    integer, intent(in) :: tags(:)
    integer, allocatable, intent(out) :: hkey(:), hval(:)
    integer, intent(out) :: bits
    integer :: i, h, mask
    bits = 4
    do while (2_i8**bits < 2_i8 * size(tags) .and. bits < 31)
      bits = bits + 1
    end do
    mask = int(2_i8**bits - 1)
    allocate(hkey(0:mask), hval(0:mask))
    hkey = 0           ! tags are >= 1, so 0 marks an empty slot
    hval = 0
    do i = 1, size(tags)
      h = hash_slot(tags(i), bits)
      do while (hkey(h) /= 0)
        h = iand(h + 1, mask)
      end do
      hkey(h) = tags(i)
      hval(h) = i
    end do
  end subroutine hash_build

  pure integer function hash_find(hkey, hval, bits, tag) result(idx)
    integer, intent(in) :: hkey(0:), hval(0:)
    integer, intent(in) :: bits, tag
    integer :: h, mask
    mask = ubound(hkey, 1)
    idx = 0
    h = hash_slot(tag, bits)
    do while (hkey(h) /= 0)
      if (hkey(h) == tag) then
        idx = hval(h)
        return
      end if
      h = iand(h + 1, mask)
    end do
  end function hash_find

  !> Knuth multiplicative hash: top bits of the low 32 bits of tag * 2654435761
  !> (the product of a 31-bit tag and this constant fits in 64 bits).
  pure integer function hash_slot(tag, bits) result(h)
    integer, intent(in) :: tag, bits
    integer(i8) :: p
    p = iand(int(tag, i8) * 2654435761_i8, 4294967295_i8)
    h = int(ishft(p, -(32 - bits)))
  end function hash_slot

  !> Position of v in the ascending array a, or 0.
  pure integer function find_sorted(a, v) result(idx)
    integer(i8), intent(in) :: a(:)
    integer(i8), intent(in) :: v
    integer :: lo, hi, mid
    idx = 0
    lo = 1
    hi = size(a)
    do while (lo <= hi)
      mid = lo + (hi - lo) / 2
      if (a(mid) == v) then
        idx = mid
        return
      else if (a(mid) < v) then
        lo = mid + 1
      else
        hi = mid - 1
      end if
    end do
  end function find_sorted

  !> Index of the entity with this tag in list, or 0.
  pure integer function find_entity(list, tag) result(e)
    type(entity_list_t), intent(in) :: list
    integer, intent(in) :: tag
    integer :: k
    e = 0
    if (list%n == 0) return
    k = find_sorted(list%skey, int(tag, i8))
    if (k > 0) e = list%sidx(k)
  end function find_entity

  !> Leave nothing half-built behind on failure.
  subroutine clear_mesh(mesh)
    type(gmsh_mesh_t), intent(inout) :: mesh
    if (allocated(mesh%node_tag)) deallocate(mesh%node_tag)
    if (allocated(mesh%x)) deallocate(mesh%x)
    if (allocated(mesh%cell_tag)) deallocate(mesh%cell_tag)
    if (allocated(mesh%cell)) deallocate(mesh%cell)
    if (allocated(mesh%cell_group)) deallocate(mesh%cell_group)
    if (allocated(mesh%facet)) deallocate(mesh%facet)
    if (allocated(mesh%facet_group)) deallocate(mesh%facet_group)
    if (allocated(mesh%groups)) deallocate(mesh%groups)
    mesh%n_nodes = 0
    mesh%n_cells = 0
    mesh%n_facets = 0
    mesh%n_groups = 0
    mesh%n_inverted = 0
  end subroutine clear_mesh

  subroutine init_entities(list)
    type(entity_list_t), intent(inout) :: list
    if (allocated(list%first)) return
    list%n = 0
    allocate(list%tag(0), list%first(1), list%phys(0), list%skey(0), list%sidx(0))
    list%first(1) = 1
  end subroutine init_entities

  subroutine push_key(key, m, dim, tag)
    integer(i8), allocatable, intent(inout) :: key(:)
    integer, intent(inout) :: m
    integer, intent(in) :: dim, tag
    integer(i8), allocatable :: tmp(:)
    if (m == size(key)) then
      allocate(tmp(2 * m + 16))
      tmp(1:m) = key(1:m)
      call move_alloc(tmp, key)
    end if
    m = m + 1
    key(m) = int(dim, i8) * dim_shift + tag
  end subroutine push_key

  subroutine grow_int(a, n)
    integer, allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    integer, allocatable :: tmp(:)
    allocate(tmp(n))
    tmp(1:size(a)) = a
    call move_alloc(tmp, a)
  end subroutine grow_int

  !> Make room for at least cap elements in list.
  subroutine reserve(list, cap)
    type(elem_list_t), intent(inout) :: list
    integer(i8), intent(in) :: cap
    integer, allocatable :: t1(:), t2(:), t3(:,:)
    integer :: n, newcap
    n = size_or_zero(list%tag)
    if (cap <= n) return
    newcap = int(max(cap, 2_i8 * n))    ! geometric growth keeps appends O(1)
    allocate(t1(newcap), t2(newcap), t3(list%nv, newcap))
    if (n > 0) then
      t1(1:n) = list%tag
      t2(1:n) = list%ref
      t3(:, 1:n) = list%node
    end if
    call move_alloc(t1, list%tag)
    call move_alloc(t2, list%ref)
    call move_alloc(t3, list%node)
  end subroutine reserve

  !> perm orders key ascending, stably; its first m entries then keep only the
  !> first of equal keys.
  subroutine sort_unique(key, perm, m)
    integer(i8), intent(in) :: key(:)
    integer, intent(out) :: perm(:)
    integer, intent(out) :: m
    integer :: i
    call sort_perm(key, perm)
    m = 0
    do i = 1, size(key)
      if (m > 0) then
        if (key(perm(i)) == key(perm(m))) cycle
      end if
      m = m + 1
      perm(m) = perm(i)
    end do
  end subroutine sort_unique

  pure integer function size_or_zero(a) result(n)
    integer, allocatable, intent(in) :: a(:)
    n = 0
    if (allocated(a)) n = size(a)
  end function size_or_zero

end module udar_gmsh
