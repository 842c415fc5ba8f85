!> Unit test of the gmsh reader (udar_gmsh).
!>
!> Usage: test_gmsh <mesh_dir> <tmp_dir>
!>   mesh_dir  tests/unit/meshes (hand-written .msh files, cube.geo, square.geo)
!>   tmp_dir   writable scratch folder (gmsh outputs, damaged copies)
!> Needs the gmsh executable on PATH for the cube and square checks.
!> Prints one line per check, "PASS name" or "FAIL name: detail", and ends
!> with error stop 1 if any check failed.
program test_gmsh
  use, intrinsic :: iso_fortran_env, only: error_unit
  use udar_kinds, only: rk, max_path_len
  use udar_gmsh, only: gmsh_mesh_t, gmsh_read
  use udar_strings, only: itoa, r2s
  implicit none

  integer :: n_pass = 0, n_fail = 0
  character(len=max_path_len) :: mesh_dir, tmp_dir
  !> The corners of the unit tetrahedron, as MSH 2.2 node lines.
  character(len=*), parameter :: corner_nodes(4) = [character(len=7) :: &
       '1 0 0 0', '2 1 0 0', '3 0 1 0', '4 0 0 1']

  if (command_argument_count() < 2) then
    write(error_unit, '(a)') 'usage: test_gmsh <mesh_dir> <tmp_dir>'
    error stop 2
  end if
  call get_command_argument(1, mesh_dir)
  mesh_dir = trim(mesh_dir)//'/meshes'   ! the argument is tests/unit
  call get_command_argument(2, tmp_dir)

  call test_two_tets('v41', trim(mesh_dir)//'/two_tets_v41.msh')
  call test_two_tets('v22', trim(mesh_dir)//'/two_tets_v22.msh')
  call test_formats_agree('two_tets', 3)
  call test_two_tris('v41', trim(mesh_dir)//'/two_tris_v41.msh')
  call test_two_tris('v22', trim(mesh_dir)//'/two_tris_v22.msh')
  call test_formats_agree('two_tris', 2)
  call test_scale()
  call test_zero_volume()
  call test_missing()
  call test_truncated()
  call test_unknown_node()
  call test_quadratic_only()
  call test_no_physical_volume()
  call test_lost_elements()
  call test_not_a_file()
  call test_coordinates_range()
  call test_2d_refused()
  call test_cube()
  call test_square()

  write(*, '(a,i0,a,i0,a)') 'test_gmsh: ', n_pass, ' passed, ', n_fail, ' failed'
  if (n_fail > 0) error stop 1

contains

  subroutine check(name, cond, detail)
    character(len=*), intent(in) :: name
    logical, intent(in) :: cond
    character(len=*), intent(in) :: detail
    if (cond) then
      n_pass = n_pass + 1
      write(*, '(a)') 'PASS '//name
    else
      n_fail = n_fail + 1
      write(*, '(a)') 'FAIL '//name//': '//detail
    end if
  end subroutine check

  function ivec(a) result(s)
    integer, intent(in) :: a(:)
    character(len=:), allocatable :: s
    integer :: i
    s = '['
    do i = 1, size(a)
      s = s//' '//itoa(a(i))
    end do
    s = s//' ]'
  end function ivec

  !> Signed measure of cell i: the volume of a tet, the area of a triangle
  !> in the (x, y) plane (positive counter-clockwise).
  real(rk) function cell_measure(m, i) result(v)
    type(gmsh_mesh_t), intent(in) :: m
    integer, intent(in) :: i
    real(rk) :: a(3), b(3), d(3)
    a = m%x(m%cell(i, 2), :) - m%x(m%cell(i, 1), :)
    b = m%x(m%cell(i, 3), :) - m%x(m%cell(i, 1), :)
    if (m%dim == 2) then
      v = (a(1) * b(2) - b(1) * a(2)) / 2.0_rk
      return
    end if
    d = m%x(m%cell(i, 4), :) - m%x(m%cell(i, 1), :)
    v = (a(1) * (b(2) * d(3) - b(3) * d(2)) - a(2) * (b(1) * d(3) - b(3) * d(1)) &
       + a(3) * (b(1) * d(2) - b(2) * d(1))) / 6.0_rk
  end function cell_measure

  !> The cells' signed measures.
  function cell_measures(m) result(v)
    type(gmsh_mesh_t), intent(in) :: m
    real(rk) :: v(m%n_cells)
    integer :: i
    do i = 1, m%n_cells
      v(i) = cell_measure(m, i)
    end do
  end function cell_measures

  !> Checks t//word//'s_positive' and t//'total_'//word: every cell's
  !> measure (word: volume or area) is positive, and they add up to total.
  subroutine check_measures(t, m, word, total)
    character(len=*), intent(in) :: t, word
    type(gmsh_mesh_t), intent(in) :: m
    real(rk), intent(in) :: total
    real(rk) :: v(m%n_cells)
    character(len=:), allocatable :: vs
    integer :: i
    v = cell_measures(m)
    vs = ''
    do i = 1, m%n_cells
      vs = vs//' '//r2s(v(i))
    end do
    call check(t//word//'s_positive', all(v > 0.0_rk), word//'s'//vs)
    call check(t//'total_'//word, abs(sum(v) - total) < 1.0e-14_rk, r2s(sum(v)))
  end subroutine check_measures

  !> Check t//'groups': the physical groups (dims(k), names(k)) are groups
  !> 1, 2, ... of m, in this order.  g: where they are (0: missing).
  subroutine check_groups(t, m, dims, names, g)
    character(len=*), intent(in) :: t, names(:)
    type(gmsh_mesh_t), intent(in) :: m
    integer, intent(in) :: dims(:)
    integer, intent(out) :: g(:)
    character(len=:), allocatable :: list
    integer :: k
    list = ''
    do k = 1, size(g)
      g(k) = group_index(m, dims(k), trim(names(k)))
      list = list//'/'//trim(names(k))
    end do
    call check(t//'groups', all(g == [(k, k = 1, size(g))]), list(2:)//' at '//ivec(g))
  end subroutine check_groups

  integer function group_index(m, dim, name) result(g)
    type(gmsh_mesh_t), intent(in) :: m
    integer, intent(in) :: dim
    character(len=*), intent(in) :: name
    do g = 1, m%n_groups
      if (m%groups(g)%dim == dim .and. m%groups(g)%name == name) return
    end do
    g = 0
  end function group_index

  logical function contains_text(s, part)
    character(len=*), intent(in) :: s, part
    contains_text = index(s, part) > 0
  end function contains_text

  subroutine write_text(path, text)
    character(len=*), intent(in) :: path, text
    integer :: u
    open(newunit=u, file=path, status='replace', action='write', access='stream', &
         form='unformatted')
    write(u) text
    close(u)
  end subroutine write_text

  function read_bytes(path) result(s)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: s
    integer :: u, n
    open(newunit=u, file=path, status='old', action='read', access='stream', form='unformatted')
    inquire(unit=u, size=n)
    allocate(character(len=n) :: s)
    read(u) s
    close(u)
  end function read_bytes

  ! --------------------------------------------------------------------------

  subroutine test_two_tets(label, path)
    character(len=*), intent(in) :: label, path
    type(gmsh_mesh_t) :: m
    logical :: ok
    character(len=:), allocatable :: err
    real(rk) :: xr(5, 3)
    integer :: g(4)
    character(len=:), allocatable :: t

    t = 'two_tets_'//label//'_'
    call gmsh_read(path, 1.0_rk, m, ok, err)
    call check(t//'read', ok, err)
    if (.not. ok) return

    call check(t//'counts', m%n_nodes == 5 .and. m%n_cells == 2 .and. m%n_facets == 4 &
               .and. m%n_groups == 4, 'nodes '//itoa(m%n_nodes)//' tets '//itoa(m%n_cells)// &
               ' tris '//itoa(m%n_facets)//' groups '//itoa(m%n_groups))
    call check(t//'node_order', all(m%node_tag == [5, 7, 10, 20, 99]), ivec(m%node_tag))
    ! rows follow node_tag: 5, 7, 10, 20, 99
    xr(1, :) = [0, 1, 0]
    xr(2, :) = [0, 0, 1]
    xr(3, :) = [0, 0, 0]
    xr(4, :) = [1, 0, 0]
    xr(5, :) = [1, 1, 1]
    call check(t//'coordinates', all(m%x == xr), 'coordinates do not follow sorted tags')
    call check(t//'tet_order', all(m%cell_tag == [42, 101]), ivec(m%cell_tag))
    ! tet 42 was written as 20 7 5 99 (inverted): expect 20 5 7 99
    call check(t//'tet42_nodes', all(m%cell(1, :) == [4, 1, 2, 5]), ivec(m%cell(1, :)))
    call check(t//'tet42_coords', all(m%x(m%cell(1, 1), :) == [1.0_rk, 0.0_rk, 0.0_rk]) .and. &
               all(m%x(m%cell(1, 2), :) == [0.0_rk, 1.0_rk, 0.0_rk]) .and. &
               all(m%x(m%cell(1, 3), :) == [0.0_rk, 0.0_rk, 1.0_rk]) .and. &
               all(m%x(m%cell(1, 4), :) == [1.0_rk, 1.0_rk, 1.0_rk]), &
               'node coordinates of tet 42 wrong')
    call check(t//'tet101_nodes', all(m%cell(2, :) == [3, 4, 1, 2]), ivec(m%cell(2, :)))
    call check(t//'n_inverted', m%n_inverted == 1, 'n_inverted = '//itoa(m%n_inverted))
    call check_measures(t, m, 'volume', 0.5_rk)

    ! bottom, group_5 (surfaces), block, group_7 (volumes), in this order
    call check_groups(t, m, [2, 2, 3, 3], [character(len=8) :: 'bottom', 'group_5', 'block', 'group_7'], g)
    if (g(3) > 0 .and. g(1) > 0 .and. g(2) > 0) then
      call check(t//'group_tags', m%groups(g(3))%tag == 1 .and. m%groups(g(1))%tag == 2 .and. &
                 m%groups(g(2))%tag == 5, 'physical tags wrong')
      call check(t//'tet_group', all(m%cell_group == g(3)), ivec(m%cell_group))
      call check(t//'tri_groups', count(m%facet_group == g(1)) == 2 .and. count(m%facet_group == g(2)) == 2, &
                 ivec(m%facet_group))
      ! rows ordered by (element tag, group): tri 3 = nodes 10 20 5 in "bottom"
      call check(t//'tri_first_row', all(m%facet(1, :) == [3, 4, 1]) .and. m%facet_group(1) == g(1), &
                 ivec(m%facet(1, :))//' group '//itoa(m%facet_group(1)))
    end if
  end subroutine test_two_tets

  !> Two meshes to compare (b read with scale_b), of dimension dim (default
  !> 3): ok if both read; err is the message of the second reading.
  subroutine read_two(file_a, file_b, scale_b, a, b, ok, err, dim)
    character(len=*), intent(in) :: file_a, file_b
    real(rk), intent(in) :: scale_b
    type(gmsh_mesh_t), intent(out) :: a, b
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: err
    integer, intent(in), optional :: dim
    logical :: oka, okb
    call gmsh_read(trim(mesh_dir)//'/'//file_a, 1.0_rk, a, oka, err, dim)
    call gmsh_read(trim(mesh_dir)//'/'//file_b, scale_b, b, okb, err, dim)
    ok = oka .and. okb
  end subroutine read_two

  !> The hand-written MSH 4.1 and 2.2 files stem_v41.msh and stem_v22.msh
  !> read (as meshes of dimension dim) identically.
  subroutine test_formats_agree(stem, dim)
    character(len=*), intent(in) :: stem
    integer, intent(in) :: dim
    type(gmsh_mesh_t) :: a, b
    logical :: ok
    character(len=:), allocatable :: err
    call read_two(stem//'_v41.msh', stem//'_v22.msh', 1.0_rk, a, b, ok, err, dim)
    if (.not. ok) then
      call check(stem//'_v41_equals_v22', .false., 'a reading failed')
      return
    end if
    call check(stem//'_v41_equals_v22', a%dim == b%dim .and. all(a%node_tag == b%node_tag) .and. &
               all(a%x == b%x) .and. all(a%cell == b%cell) .and. all(a%cell_tag == b%cell_tag) .and. &
               all(a%cell_group == b%cell_group) .and. all(a%facet == b%facet) .and. &
               all(a%facet_group == b%facet_group) .and. all(a%groups%tag == b%groups%tag) .and. &
               all(a%groups%dim == b%groups%dim) .and. all(a%groups%name == b%groups%name) .and. &
               a%n_inverted == b%n_inverted, 'v41 and v22 readings differ')
  end subroutine test_formats_agree

  !> The unit square of two triangles read as a 2D mesh.
  subroutine test_two_tris(label, path)
    character(len=*), intent(in) :: label, path
    type(gmsh_mesh_t) :: m
    logical :: ok
    character(len=:), allocatable :: err, t
    real(rk) :: xr(4, 3)
    integer :: g(4)

    t = 'two_tris_'//label//'_'
    call gmsh_read(path, 1.0_rk, m, ok, err, dim=2)
    call check(t//'read', ok, err)
    if (.not. ok) return

    call check(t//'counts', m%dim == 2 .and. m%n_nodes == 4 .and. m%n_cells == 2 .and. &
               m%n_facets == 3 .and. m%n_groups == 4 .and. size(m%cell, 2) == 3 .and. &
               size(m%facet, 2) == 2 .and. size(m%x, 2) == 3, 'dim '//itoa(m%dim)// &
               ' nodes '//itoa(m%n_nodes)//' triangles '//itoa(m%n_cells)//' lines '// &
               itoa(m%n_facets)//' groups '//itoa(m%n_groups))
    call check(t//'node_order', all(m%node_tag == [5, 10, 20, 30]), ivec(m%node_tag))
    ! rows follow node_tag: 5, 10, 20, 30
    xr = reshape([0, 0, 1, 1, &        ! x
                  1, 0, 0, 1, &        ! y
                  0, 0, 0, 0], [4, 3]) ! z
    call check(t//'coordinates', all(m%x == xr), 'coordinates do not follow sorted tags')
    call check(t//'triangle_order', all(m%cell_tag == [3, 7]), ivec(m%cell_tag))
    ! triangle 3 was written clockwise as 10 5 30: expect 10 30 5
    call check(t//'tri3_nodes', all(m%cell(1, :) == [2, 4, 1]), ivec(m%cell(1, :)))
    call check(t//'tri7_nodes', all(m%cell(2, :) == [2, 3, 4]), ivec(m%cell(2, :)))
    call check(t//'n_inverted', m%n_inverted == 1, 'n_inverted = '//itoa(m%n_inverted))
    call check_measures(t, m, 'area', 1.0_rk)

    ! axis, bottom, group_9 (curves), plate (surface), in this order
    call check_groups(t, m, [1, 1, 1, 2], [character(len=8) :: 'axis', 'bottom', 'group_9', 'plate'], g)
    if (any(g == 0)) return
    call check(t//'group_tags', all(m%groups(g)%tag == [1, 2, 9, 1]) .and. &
               all(m%groups(g)%dim == [1, 1, 1, 2]), 'physical tags wrong')
    call check(t//'triangle_group', all(m%cell_group == g(4)), ivec(m%cell_group))
    ! rows ordered by (element tag, group): line 11 (nodes 5 10) in "axis",
    ! line 12 (10 20) in "bottom" and in group 9; line 13 is in no group
    call check(t//'line_rows', all(m%facet(1, :) == [1, 2]) .and. all(m%facet(2, :) == [2, 3]) .and. &
               all(m%facet(3, :) == [2, 3]) .and. all(m%facet_group == g(1:3)), &
               ivec(m%facet(:, 1))//' '//ivec(m%facet(:, 2))//' groups '//ivec(m%facet_group))
    call check(t//'axis_on_x0', all(m%x(m%facet(1, :), 1) == 0.0_rk), 'axis line not at x = 0')
  end subroutine test_two_tris

  subroutine test_scale()
    type(gmsh_mesh_t) :: a, b
    logical :: ok
    character(len=:), allocatable :: err
    call read_two('two_tets_v41.msh', 'two_tets_v41.msh', 1.0e-3_rk, a, b, ok, err)
    call check('scale_read', ok, err)
    if (.not. ok) return
    call check('scale_applied', all(b%x == a%x * 1.0e-3_rk) .and. &
               all(b%x(5, :) == [1.0e-3_rk, 1.0e-3_rk, 1.0e-3_rk]), &
               'x(99) = '//r2s(b%x(5, 1)))
    call check('scale_orientation', b%n_inverted == 1 .and. all(b%cell == a%cell), &
               'orientation changed with scale')
  end subroutine test_scale

  subroutine test_zero_volume()
    type(gmsh_mesh_t) :: m
    logical :: ok
    character(len=:), allocatable :: err
    call gmsh_read(trim(mesh_dir)//'/zero_volume.msh', 1.0_rk, m, ok, err)
    call check('zero_volume_fails', .not. ok, 'flat tet accepted')
    call check('zero_volume_message', contains_text(err, 'element tags: 17') .and. &
               contains_text(err, 'zero_volume.msh') .and. .not. contains_text(err, ' 3 '), &
               'message: '//err)
    call check('zero_volume_mesh_empty', m%n_cells == 0 .and. .not. allocated(m%x), &
               'mesh not cleared on failure')
  end subroutine test_zero_volume

  subroutine test_missing()
    type(gmsh_mesh_t) :: m
    logical :: ok
    character(len=:), allocatable :: err, path
    path = trim(tmp_dir)//'/no_such_mesh.msh'
    call gmsh_read(path, 1.0_rk, m, ok, err)
    call check('missing_file', .not. ok .and. contains_text(err, path), 'message: '//err)
  end subroutine test_missing

  !> A bad mesh: text written to tmp_dir/file must be rejected, when read as
  !> a mesh of dimension dim (default 3), with a message holding frag ('' for
  !> any), frag2 if given and, if with_path, the file's path.
  subroutine expect_rejected(name, file, text, frag, with_path, dim, frag2)
    character(len=*), intent(in) :: name, file, text, frag
    logical, intent(in) :: with_path
    integer, intent(in), optional :: dim
    character(len=*), intent(in), optional :: frag2
    type(gmsh_mesh_t) :: m
    logical :: ok, has2
    character(len=:), allocatable :: err, path
    path = trim(tmp_dir)//'/'//file
    call write_text(path, text)
    call gmsh_read(path, 1.0_rk, m, ok, err, dim)
    has2 = .true.
    if (present(frag2)) has2 = contains_text(err, frag2)
    call check(name, .not. ok .and. contains_text(err, frag) .and. has2 .and. &
               (contains_text(err, path) .or. .not. with_path), 'message: '//err)
  end subroutine expect_rejected

  !> Damaged copies of the ASCII file: cut in the element block, before its
  !> end marker; and files that are no (supported) mesh at all.
  subroutine test_truncated()
    character(len=:), allocatable :: text
    character(len=*), parameter :: lf = achar(10)
    text = read_bytes(trim(mesh_dir)//'/two_tets_v41.msh')
    call expect_rejected('truncated_ascii', 'truncated_v41.msh', &
                         text(1:index(text, '101 10 20') + 5), '', .true.)
    call expect_rejected('missing_end_section', 'bad_end.msh', &
                         text(1:index(text, '$EndElements') - 1), '$EndElements', .true.)
    call expect_rejected('not_a_mesh', 'not_a_mesh.msh', 'hello'//lf, 'MeshFormat', .false.)
    call expect_rejected('unsupported_version', 'v40.msh', &
                         '$MeshFormat'//lf//'4 0 8'//lf//'$EndMeshFormat'//lf, &
                         'unsupported MSH format', .true.)
  end subroutine test_truncated

  subroutine test_unknown_node()
    character(len=:), allocatable :: text
    integer :: k
    text = read_bytes(trim(mesh_dir)//'/two_tets_v22.msh')
    k = index(text, '42 4 2 1 1 20 7 5 99')
    text = text(1:k-1)//'42 4 2 1 1 20 7 5 1234'//text(k+20:)
    call expect_rejected('unknown_node_tag', 'unknown_node.msh', text, '1234', .true.)
  end subroutine test_unknown_node

  !> A MSH 2.2 ASCII file with these $Nodes and $Elements lines (and these
  !> $PhysicalNames lines if given).
  function msh22(nodes, elements, names) result(text)
    character(len=*), intent(in) :: nodes(:), elements(:)
    character(len=*), intent(in), optional :: names(:)
    character(len=:), allocatable :: text
    character(len=*), parameter :: lf = achar(10)
    integer :: i
    text = '$MeshFormat'//lf//'2.2 0 8'//lf//'$EndMeshFormat'//lf
    if (present(names)) then
      text = text//'$PhysicalNames'//lf//itoa(size(names))//lf
      do i = 1, size(names)
        text = text//trim(names(i))//lf
      end do
      text = text//'$EndPhysicalNames'//lf
    end if
    text = text//'$Nodes'//lf//itoa(size(nodes))//lf
    do i = 1, size(nodes)
      text = text//trim(nodes(i))//lf
    end do
    text = text//'$EndNodes'//lf//'$Elements'//lf//itoa(size(elements))//lf
    do i = 1, size(elements)
      text = text//trim(elements(i))//lf
    end do
    text = text//'$EndElements'//lf
  end function msh22

  !> A 10-node tet (gmsh type 11) in a physical volume.
  subroutine test_quadratic_only()
    call expect_rejected('quadratic_tets_rejected', 'tet10.msh', msh22([character(len=12) :: &
         corner_nodes, '5 0.5 0 0', '6 0.5 0.5 0', '7 0 0.5 0', '8 0 0 0.5', '9 0 0.5 0.5', &
         '10 0.5 0 0.5'], ['1 11 2 1 1 1 2 3 4 5 6 7 8 9 10']), 'element 1 is a 10-node (second-order) tetrahedron (gmsh type 11)', .false.)
  end subroutine test_quadratic_only

  !> Elements that used to be dropped without a word: a prism, a hexahedron
  !> and a pyramid next to a tet, an element type gmsh does not have, two
  !> different tets under one tag (MSH 2.2 and 4.1); the same tet listed once
  !> per physical group (MSH 2.2) is still read.
  subroutine test_lost_elements()
    character(len=12), parameter :: nodes(9) = [character(len=12) :: corner_nodes, &
         '5 1 1 0', '6 1 0 1', '7 0 1 1', '8 1 1 1', '9 0.5 0.5 2']
    character(len=*), parameter :: tet = '1 4 2 1 1 1 2 3 4'
    character(len=*), parameter :: lf = achar(10)
    type(gmsh_mesh_t) :: m
    logical :: ok
    character(len=:), allocatable :: err, path
    call expect_rejected('prism_rejected', 'prism.msh', msh22(nodes, &
         [character(len=40) :: tet, '2 6 2 1 1 2 3 5 6 7 8']), 'element 2 is a 6-node prism (gmsh type 6)', .true.)
    call expect_rejected('hexahedron_rejected', 'hex.msh', msh22(nodes, &
         [character(len=40) :: tet, '7 5 2 1 1 1 2 5 3 4 6 8 7']), 'element 7 is an 8-node hexahedron', .true.)
    call expect_rejected('pyramid_rejected', 'pyramid.msh', msh22(nodes, &
         [character(len=40) :: tet, '3 7 2 1 1 4 6 8 7 9']), 'element 3 is a 5-node pyramid', .true.)
    call expect_rejected('prism_outside_groups_rejected', 'prism0.msh', msh22(nodes, &
         [character(len=40) :: tet, '2 6 2 0 1 2 3 5 6 7 8']), 'element 2 is a 6-node prism', .true.)
    call expect_rejected('unknown_type_999', 'type999.msh', msh22(nodes, &
         [character(len=40) :: tet, '2 999 2 1 1 2 3 5']), 'element 2 has element type 999', .true.)
    call expect_rejected('duplicate_tag_v22', 'dup22.msh', msh22(nodes, &
         [character(len=40) :: tet, '1 4 2 1 1 2 3 4 8']), 'element tag 1 is used by a tetrahedron', .true.)
    call expect_rejected('duplicate_tag_tet_triangle', 'dup_tri.msh', msh22(nodes, &
         [character(len=40) :: tet, '1 2 2 2 1 1 2 3']), 'and by a triangle', .true.)
    call expect_rejected('prism_v41', 'prism41.msh', '$MeshFormat'//lf//'4.1 0 8'//lf//'$EndMeshFormat'//lf// &
         '$Entities'//lf//'0 0 0 1'//lf//'1 0 0 0 1 1 1 1 1 0'//lf//'$EndEntities'//lf// &
         '$Nodes'//lf//'1 6 1 6'//lf//'3 1 0 6'//lf//'1'//lf//'2'//lf//'3'//lf//'4'//lf//'5'//lf//'6'//lf// &
         '0 0 0'//lf//'1 0 0'//lf//'0 1 0'//lf//'0 0 1'//lf//'1 0 1'//lf//'0 1 1'//lf//'$EndNodes'//lf// &
         '$Elements'//lf//'2 2 1 5'//lf//'3 1 4 1'//lf//'1 1 2 3 4'//lf//'3 1 6 1'//lf//'5 1 2 3 4 5 6'//lf// &
         '$EndElements'//lf, 'element 5 is a 6-node prism', .true.)
    call expect_rejected('duplicate_tag_v41', 'dup41.msh', '$MeshFormat'//lf//'4.1 0 8'//lf//'$EndMeshFormat'//lf// &
         '$Entities'//lf//'0 0 0 1'//lf//'1 0 0 0 1 1 1 1 1 0'//lf//'$EndEntities'//lf// &
         '$Nodes'//lf//'1 5 1 5'//lf//'3 1 0 5'//lf//'1'//lf//'2'//lf//'3'//lf//'4'//lf//'5'//lf// &
         '0 0 0'//lf//'1 0 0'//lf//'0 1 0'//lf//'0 0 1'//lf//'1 1 1'//lf//'$EndNodes'//lf// &
         '$Elements'//lf//'1 2 1 2'//lf//'3 1 4 2'//lf//'1 1 2 3 4'//lf//'1 2 3 4 5'//lf// &
         '$EndElements'//lf, 'element tag 1 is used by', .true.)
    ! the same element in two physical volumes (MSH 2.2 repeats the line)
    path = trim(tmp_dir)//'/two_groups.msh'
    call write_text(path, msh22(nodes, [character(len=40) :: tet, '1 4 2 2 1 1 2 3 4', '2 4 2 2 1 2 3 4 8']))
    call gmsh_read(path, 1.0_rk, m, ok, err)
    call check('same_tet_in_two_groups_read', ok .and. m%n_cells == 2, 'message: '//err)
  end subroutine test_lost_elements

  !> A directory or a FIFO is refused before it is opened (a FIFO would
  !> block the open forever).
  subroutine test_not_a_file()
    type(gmsh_mesh_t) :: m
    logical :: ok
    character(len=:), allocatable :: err
    integer :: st
    call gmsh_read(trim(tmp_dir), 1.0_rk, m, ok, err)
    call check('directory_refused', .not. ok .and. contains_text(err, 'is a directory') .and. &
               contains_text(err, trim(tmp_dir)), 'message: '//err)
    call execute_command_line('rm -f '//trim(tmp_dir)//'/fifo.msh; mkfifo '//trim(tmp_dir)//'/fifo.msh', &
                              exitstat=st)
    if (st /= 0) return
    call gmsh_read(trim(tmp_dir)//'/fifo.msh', 1.0_rk, m, ok, err)
    call check('fifo_refused', .not. ok .and. contains_text(err, 'FIFO') .and. &
               contains_text(err, 'fifo.msh'), 'message: '//err)
  end subroutine test_not_a_file

  !> Coordinates that are not finite, or too large once scaled, are named as
  !> such (they used to be reported as degenerate tetrahedra).
  subroutine test_coordinates_range()
    type(gmsh_mesh_t) :: m
    logical :: ok
    character(len=:), allocatable :: err, path
    path = trim(tmp_dir)//'/big.msh'
    call write_text(path, msh22([character(len=12) :: '1 0 0 0', '2 1e308 0 0', '3 0 1 0', '4 0 0 1'], &
                    ['1 4 2 1 1 1 2 3 4']))
    call gmsh_read(path, 1.0_rk, m, ok, err)
    call check('coordinate_1e308', .not. ok .and. contains_text(err, 'node 2 has coordinates out of range'), &
               'message: '//err)
    call write_text(path, msh22(corner_nodes, ['1 4 2 1 1 1 2 3 4']))
    call gmsh_read(path, 1.0e300_rk, m, ok, err)
    call check('scale_1e300', .not. ok .and. contains_text(err, 'out of range') .and. &
               contains_text(err, 'scale'), 'message: '//err)
  end subroutine test_coordinates_range

  !> A linear tet in no physical group (its physical tag is 0).
  subroutine test_no_physical_volume()
    call expect_rejected('no_physical_volume', 'no_physical.msh', &
         msh22(corner_nodes, ['1 4 2 0 1 1 2 3 4']), 'physical volume', .false.)
  end subroutine test_no_physical_volume

  !> What a 2D reading refuses, each with a message that says what to do; and
  !> what it still accepts.
  subroutine test_2d_refused()
    character(len=12), parameter :: square(5) = [character(len=12) :: &
         '1 0 0 0', '2 1 0 0', '3 1 1 0', '4 0 1 0', '5 2 0 0']
    character(len=*), parameter :: tri = '1 2 2 1 1 1 2 3'
    type(gmsh_mesh_t) :: m
    logical :: ok
    character(len=:), allocatable :: err, path

    ! a 3D mesh
    call expect_rejected('2d_of_tets_v41', 'tets41_2d.msh', read_bytes(trim(mesh_dir)//'/two_tets_v41.msh'), &
         'element 101 is a tetrahedron (gmsh type 4): the mesh is 3D but a 2D calculation was asked for', &
         .true., 2, 'gmsh -2')
    call expect_rejected('2d_of_tets_v22', 'tets22_2d.msh', read_bytes(trim(mesh_dir)//'/two_tets_v22.msh'), &
         'element 101 is a tetrahedron (gmsh type 4): the mesh is 3D', .true., 2, 'gmsh -2')
    call expect_rejected('2d_of_prism', 'prism_2d.msh', msh22(square, [character(len=40) :: tri, &
         '2 6 2 0 1 1 2 3 4 5 1']), 'element 2 is a 6-node prism (gmsh type 6): the mesh is 3D', &
         .true., 2, 'gmsh -2')
    ! quadrangles and second-order triangles, in a physical group or not
    call expect_rejected('2d_quad_refused', 'quad.msh', msh22(square, ['1 3 2 1 1 1 2 3 4']), &
         'element 1 is a 4-node quadrilateral (gmsh type 3): udar takes only 3-node triangles (type 2)', &
         .true., 2, 'no Recombine')
    call expect_rejected('2d_quad_outside_groups_refused', 'quad0.msh', msh22(square, &
         [character(len=40) :: tri, '2 3 2 0 1 1 2 3 4']), 'element 2 is a 4-node quadrilateral', .true., 2)
    call expect_rejected('2d_tri6_refused', 'tri6.msh', msh22([character(len=12) :: square, &
         '6 0.5 0.5 0'], ['1 9 2 1 1 1 2 3 5 6 4']), 'element 1 is a 6-node (second-order) triangle (gmsh type 9)', &
         .true., 2, 'gmsh -2 -order 1')
    ! out of the plane z = 0: the first node by tag is named
    call expect_rejected('2d_node_off_plane', 'off_plane.msh', msh22([character(len=12) :: '1 0 0 0', &
         '2 1 0 0', '3 1 1 0.25', '4 0 1 -1'], [tri]), 'node 3 has z = 0.25', .true., 2, 'plane z = 0')
    path = trim(tmp_dir)//'/tiny_z.msh'
    call write_text(path, msh22([character(len=12) :: '1 0 0 0', '2 1 0 1e-14', '3 1 1 0'], [tri]))
    call gmsh_read(path, 1.0_rk, m, ok, err, dim=2)
    call check('2d_rounding_z_accepted_and_put_on_the_plane', ok .and. m%n_cells == 1 .and. all(m%x(:,3) == 0.0_rk), &
               'message: '//err)
    ! no physical surface, or none holding a triangle
    call expect_rejected('2d_no_physical_surface', 'no_surface.msh', msh22(square, &
         [character(len=40) :: '1 2 2 0 1 1 2 3', '2 1 2 5 1 1 2']), 'no physical surface group: define one ("Physical '// &
         'Surface") so the solver knows which triangles form the body', .true., 2)
    call expect_rejected('2d_no_triangle_in_group', 'empty_surface.msh', msh22(square, &
         ['1 2 2 0 1 1 2 3'], ['2 1 "plate"']), 'no 3-node triangles belong to a physical surface group', .true., 2)
    ! flat triangle; one tag for a triangle and a line
    call expect_rejected('2d_zero_area', 'zero_area.msh', msh22(square, [character(len=40) :: tri, &
         '8 2 2 1 1 1 2 5']), '1 degenerate (zero-area) triangles', .true., 2, 'element tags: 8')
    call expect_rejected('2d_duplicate_tag_line_triangle', 'dup_line.msh', msh22(square, &
         [character(len=40) :: tri, '1 1 2 2 1 1 2']), &
         'element tag 1 is used by a triangle (nodes 1 2 3) and by a line (nodes 1 2)', .true., 2)
    ! a 2D mesh read in 3D, as before; a dimension that is neither
    call expect_rejected('3d_of_two_tris', 'tris_3d.msh', read_bytes(trim(mesh_dir)//'/two_tris_v41.msh'), &
         'no physical volume group', .true.)
    call expect_rejected('dim_1_refused', 'dim1.msh', msh22(square, [tri]), 'must be 2 or 3', .true., 1)
  end subroutine test_2d_refused

  !> Mesh mesh_dir/stem.geo with gmsh -dim and these options into
  !> tmp_dir/out (a check); ok if gmsh succeeded.
  subroutine run_gmsh(stem, dim, options, out, ok)
    character(len=*), intent(in) :: stem, options, out
    integer, intent(in) :: dim
    logical, intent(out) :: ok
    character(len=:), allocatable :: cmd, path
    integer :: stat, cstat
    path = trim(tmp_dir)//'/'//out
    cmd = 'gmsh -'//itoa(dim)//' '//options//' "'//trim(mesh_dir)//'/'//stem//'.geo" -o "'//path// &
          '" > "'//path//'.log" 2>&1'
    call execute_command_line(cmd, exitstat=stat, cmdstat=cstat)
    ok = stat == 0 .and. cstat == 0
    call check(stem//'_gmsh_'//out, ok, 'command failed: '//cmd)
  end subroutine run_gmsh

  !> The mesh gmsh makes of stem.geo, written as MSH 4.1 binary, 4.1 ASCII and
  !> 2.2 ASCII (tmp_dir/stem_bin.msh, _v41, _v22) and read as meshes m(1:3)
  !> of dimension dim, must read identically: positive cells of total measure
  !> total, the physical group body (of dimension dim) and the facet groups
  !> faces(j) (of dimension dim-1) whose nodes lie on the plane
  !> x(:, axis(j)) = at(j).  ok: all three were written and read.
  subroutine check_formats(stem, dim, total, body, faces, axis, at, m, ok)
    character(len=*), intent(in) :: stem, body, faces(2)
    integer, intent(in) :: dim, axis(2)
    real(rk), intent(in) :: total, at(2)
    type(gmsh_mesh_t), intent(out) :: m(3)
    logical, intent(out) :: ok
    character(len=*), parameter :: fmts(3) = [character(len=24) :: &
         '-format msh41 -bin', '-format msh41', '-format msh22']
    character(len=*), parameter :: suffix(3) = [character(len=8) :: '_bin.msh', '_v41.msh', '_v22.msh']
    character(len=*), parameter :: measure(2:3) = [character(len=6) :: 'area', 'volume']
    character(len=*), parameter :: facet_word(2:3) = [character(len=7) :: 'curve', 'surface']
    character(len=:), allocatable :: err, name
    integer :: k, i, j, g(2), nf(2, 3), nn(3), nt(3)
    real(rk) :: tot(3), perr
    logical :: same

    do k = 1, 3
      name = stem//trim(suffix(k))
      call run_gmsh(stem, dim, trim(fmts(k)), name, ok)
      if (.not. ok) return
      call gmsh_read(trim(tmp_dir)//'/'//name, 1.0_rk, m(k), ok, err, dim)
      call check(stem//'_read_'//name, ok, err)
      if (.not. ok) return
      tot(k) = sum(cell_measures(m(k)))
      call check(stem//'_'//trim(measure(dim))//'_'//name, abs(tot(k) - total) < 1.0e-12_rk .and. &
                 all(cell_measures(m(k)) > 0.0_rk), r2s(tot(k))//', smallest cell '// &
                 r2s(minval(cell_measures(m(k)))))
      g = [group_index(m(k), dim - 1, trim(faces(1))), group_index(m(k), dim - 1, trim(faces(2)))]
      ok = all(g > 0) .and. group_index(m(k), dim, body) > 0
      call check(stem//'_groups_'//name, ok, trim(faces(1))//'/'//trim(faces(2))//'/'//body// &
                 ' not all found')
      if (.not. ok) return
      ! every facet of group j lies on its plane
      perr = 0.0_rk
      do j = 1, 2
        nf(j, k) = count(m(k)%facet_group == g(j))
        do i = 1, m(k)%n_facets
          if (m(k)%facet_group(i) == g(j)) &
            perr = max(perr, maxval(abs(m(k)%x(m(k)%facet(i, :), axis(j)) - at(j))))
        end do
      end do
      call check(stem//'_'//trim(facet_word(dim))//'_nodes_'//name, all(nf(:, k) > 0) .and. &
                 perr < 1.0e-12_rk, trim(faces(1))//' '//itoa(nf(1, k))//' '//trim(faces(2))//' '// &
                 itoa(nf(2, k))//' max |plane error| '//r2s(perr))
    end do
    same = .true.
    nn = [(m(k)%n_nodes, k = 1, 3)]
    nt = [(m(k)%n_cells, k = 1, 3)]
    do k = 2, 3
      same = same .and. nn(k) == nn(1) .and. nt(k) == nt(1) .and. all(nf(:, k) == nf(:, 1)) .and. &
             abs(tot(k) - tot(1)) < 1.0e-12_rk
    end do
    call check(stem//'_formats_agree', same, 'nodes '//ivec(nn)//' cells '//ivec(nt)//' '// &
               trim(faces(1))//' '//ivec(nf(1, :))//' '//trim(faces(2))//' '//ivec(nf(2, :)))
    if (same) then
      call check(stem//'_connectivity_agree', all(m(1)%cell == m(2)%cell) .and. &
                 all(m(1)%cell == m(3)%cell) .and. all(m(1)%node_tag == m(3)%node_tag) .and. &
                 all(m(1)%facet == m(2)%facet) .and. all(m(1)%facet == m(3)%facet) .and. &
                 m(1)%n_inverted == m(2)%n_inverted .and. m(1)%n_inverted == m(3)%n_inverted .and. &
                 maxval(abs(m(1)%x - m(2)%x)) < 1.0e-15_rk, 'connectivity or coordinates differ')
    end if
  end subroutine check_formats

  !> The unit cube meshed by gmsh -3 in three formats; cut in the middle, or
  !> read as a 2D mesh, its binary file is refused.
  subroutine test_cube()
    type(gmsh_mesh_t) :: m(3)
    logical :: ok
    character(len=:), allocatable :: text

    call check_formats('cube', 3, 1.0_rk, 'cube', [character(len=8) :: 'zmin', 'zmax'], [3, 3], &
                       [0.0_rk, 1.0_rk], m, ok)
    if (.not. ok) return
    ! a binary file cut in the middle must be rejected, not misread
    text = read_bytes(trim(tmp_dir)//'/cube_bin.msh')
    call expect_rejected('truncated_binary', 'cube_bin_truncated.msh', text(1:len(text) / 2), '', .true.)
    call expect_rejected('cube_bin_read_2d_refused', 'cube_bin_2d.msh', text, &
                         'is a tetrahedron (gmsh type 4): the mesh is 3D', .true., 2, 'gmsh -2')
  end subroutine test_cube

  !> The 1 x 2 rectangle meshed by gmsh -2 in three formats (the binary
  !> reading agrees with the ASCII ones); meshed with quadrangles or
  !> second-order triangles, it is refused.
  subroutine test_square()
    type(gmsh_mesh_t) :: m(3)
    logical :: ok

    call check_formats('square', 2, 2.0_rk, 'plate', [character(len=8) :: 'axis', 'bottom'], [1, 2], &
                       [0.0_rk, 0.0_rk], m, ok)
    if (.not. ok) return
    call check('square_dim', all(m(:)%dim == 2) .and. size(m(1)%cell, 2) == 3 .and. &
               size(m(1)%facet, 2) == 2, 'dim '//itoa(m(1)%dim))
    call run_gmsh('square', 2, '-format msh41 -bin -string "Mesh.RecombineAll = 1;"', 'square_quads.msh', ok)
    if (ok) call expect_rejected('square_quads_refused', 'square_quads_copy.msh', &
                                 read_bytes(trim(tmp_dir)//'/square_quads.msh'), &
                                 'is a 4-node quadrilateral (gmsh type 3)', .true., 2, 'no Recombine')
    call run_gmsh('square', 2, '-format msh41 -order 2', 'square_order2.msh', ok)
    if (ok) call expect_rejected('square_order2_refused', 'square_order2_copy.msh', &
                                 read_bytes(trim(tmp_dir)//'/square_order2.msh'), &
                                 'is a 6-node (second-order) triangle (gmsh type 9)', .true., 2, 'gmsh -2 -order 1')
  end subroutine test_square

end program test_gmsh
