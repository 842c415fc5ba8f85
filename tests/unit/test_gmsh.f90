!> Unit test of the gmsh reader (udar_gmsh).
!>
!> Usage: test_gmsh <mesh_dir> <tmp_dir>
!>   mesh_dir  tests/unit/meshes (hand-written .msh files and cube.geo)
!>   tmp_dir   writable scratch folder (gmsh outputs, damaged copies)
!> Needs the gmsh executable on PATH for the cube checks.
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
  call test_formats_agree()
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
  call test_cube()

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

  !> Signed volume of tet i.
  real(rk) function tet_volume(m, i) result(v)
    type(gmsh_mesh_t), intent(in) :: m
    integer, intent(in) :: i
    real(rk) :: a(3), b(3), d(3)
    a = m%x(m%cell(i, 2), :) - m%x(m%cell(i, 1), :)
    b = m%x(m%cell(i, 3), :) - m%x(m%cell(i, 1), :)
    d = m%x(m%cell(i, 4), :) - m%x(m%cell(i, 1), :)
    v = (a(1) * (b(2) * d(3) - b(3) * d(2)) - a(2) * (b(1) * d(3) - b(3) * d(1)) &
       + a(3) * (b(1) * d(2) - b(2) * d(1))) / 6.0_rk
  end function tet_volume

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
    real(rk) :: xr(5, 3), vol
    integer :: i, gb, g5, gv, g7
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
    vol = 0.0_rk
    do i = 1, m%n_cells
      vol = vol + tet_volume(m, i)
    end do
    call check(t//'volumes_positive', tet_volume(m, 1) > 0.0_rk .and. tet_volume(m, 2) > 0.0_rk, &
               'volumes '//r2s(tet_volume(m, 1))//' '//r2s(tet_volume(m, 2)))
    call check(t//'total_volume', abs(vol - 0.5_rk) < 1.0e-14_rk, r2s(vol))

    gb = group_index(m, 2, 'bottom')
    g5 = group_index(m, 2, 'group_5')
    gv = group_index(m, 3, 'block')
    g7 = group_index(m, 3, 'group_7')
    call check(t//'groups', gb == 1 .and. g5 == 2 .and. gv == 3 .and. g7 == 4, &
               'bottom/group_5/block/group_7 at '//ivec([gb, g5, gv, g7]))
    if (gv > 0 .and. gb > 0 .and. g5 > 0) then
      call check(t//'group_tags', m%groups(gv)%tag == 1 .and. m%groups(gb)%tag == 2 .and. &
                 m%groups(g5)%tag == 5, 'physical tags wrong')
      call check(t//'tet_group', all(m%cell_group == gv), ivec(m%cell_group))
      call check(t//'tri_groups', count(m%facet_group == gb) == 2 .and. count(m%facet_group == g5) == 2, &
                 ivec(m%facet_group))
      ! rows ordered by (element tag, group): tri 3 = nodes 10 20 5 in "bottom"
      call check(t//'tri_first_row', all(m%facet(1, :) == [3, 4, 1]) .and. m%facet_group(1) == gb, &
                 ivec(m%facet(1, :))//' group '//itoa(m%facet_group(1)))
    end if
  end subroutine test_two_tets

  !> Two meshes to compare (b read with scale_b): ok if both read; err is the
  !> message of the second reading.
  subroutine read_two(file_a, file_b, scale_b, a, b, ok, err)
    character(len=*), intent(in) :: file_a, file_b
    real(rk), intent(in) :: scale_b
    type(gmsh_mesh_t), intent(out) :: a, b
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: err
    logical :: oka, okb
    call gmsh_read(trim(mesh_dir)//'/'//file_a, 1.0_rk, a, oka, err)
    call gmsh_read(trim(mesh_dir)//'/'//file_b, scale_b, b, okb, err)
    ok = oka .and. okb
  end subroutine read_two

  subroutine test_formats_agree()
    type(gmsh_mesh_t) :: a, b
    logical :: ok
    character(len=:), allocatable :: err
    call read_two('two_tets_v41.msh', 'two_tets_v22.msh', 1.0_rk, a, b, ok, err)
    if (.not. ok) then
      call check('two_tets_v41_equals_v22', .false., 'a reading failed')
      return
    end if
    call check('two_tets_v41_equals_v22', all(a%node_tag == b%node_tag) .and. all(a%x == b%x) &
               .and. all(a%cell == b%cell) .and. all(a%cell_tag == b%cell_tag) .and. &
               all(a%facet == b%facet) .and. all(a%facet_group == b%facet_group) .and. &
               all(a%groups%tag == b%groups%tag) .and. all(a%groups%name == b%groups%name), &
               'v41 and v22 readings differ')
  end subroutine test_formats_agree

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

  !> A bad mesh: text written to tmp_dir/file must be rejected with a message
  !> holding frag ('' for any) and, if with_path, the file's path.
  subroutine expect_rejected(name, file, text, frag, with_path)
    character(len=*), intent(in) :: name, file, text, frag
    logical, intent(in) :: with_path
    type(gmsh_mesh_t) :: m
    logical :: ok
    character(len=:), allocatable :: err, path
    path = trim(tmp_dir)//'/'//file
    call write_text(path, text)
    call gmsh_read(path, 1.0_rk, m, ok, err)
    call check(name, .not. ok .and. contains_text(err, frag) .and. &
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

  !> A MSH 2.2 ASCII file with these $Nodes and $Elements lines.
  function msh22(nodes, elements) result(text)
    character(len=*), intent(in) :: nodes(:), elements(:)
    character(len=:), allocatable :: text
    character(len=*), parameter :: lf = achar(10)
    integer :: i
    text = '$MeshFormat'//lf//'2.2 0 8'//lf//'$EndMeshFormat'//lf//'$Nodes'//lf//itoa(size(nodes))//lf
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

  !> The same gmsh mesh written as MSH 4.1 binary, 4.1 ASCII and 2.2 ASCII
  !> must read identically.
  subroutine test_cube()
    character(len=*), parameter :: fmts(3) = [character(len=24) :: &
         '-format msh41 -bin', '-format msh41', '-format msh22']
    character(len=*), parameter :: names(3) = [character(len=16) :: &
         'cube_bin.msh', 'cube_v41.msh', 'cube_v22.msh']
    type(gmsh_mesh_t) :: m(3)
    logical :: ok(3), same
    character(len=:), allocatable :: err, cmd, out, text
    integer :: k, i, stat, cstat, gz0, gz1, nz0(3), nz1(3)
    real(rk) :: vol(3), zerr
    integer :: nn(3), nt(3)

    cmd = ''
    do k = 1, 3
      out = trim(tmp_dir)//'/'//trim(names(k))
      cmd = 'gmsh -3 '//trim(fmts(k))//' "'//trim(mesh_dir)//'/cube.geo" -o "'//out// &
            '" > "'//out//'.log" 2>&1'
      call execute_command_line(cmd, exitstat=stat, cmdstat=cstat)
      call check('cube_gmsh_'//trim(names(k)), stat == 0 .and. cstat == 0, &
                 'command failed: '//cmd)
      call gmsh_read(out, 1.0_rk, m(k), ok(k), err)
      call check('cube_read_'//trim(names(k)), ok(k), err)
      if (.not. ok(k)) return
      vol(k) = 0.0_rk
      do i = 1, m(k)%n_cells
        vol(k) = vol(k) + tet_volume(m(k), i)
      end do
      call check('cube_volume_'//trim(names(k)), abs(vol(k) - 1.0_rk) < 1.0e-12_rk, r2s(vol(k)))
      gz0 = group_index(m(k), 2, 'zmin')
      gz1 = group_index(m(k), 2, 'zmax')
      call check('cube_groups_'//trim(names(k)), gz0 > 0 .and. gz1 > 0 .and. &
                 group_index(m(k), 3, 'cube') > 0, 'zmin/zmax/cube not all found')
      if (gz0 == 0 .or. gz1 == 0) return
      nz0(k) = count(m(k)%facet_group == gz0)
      nz1(k) = count(m(k)%facet_group == gz1)
      ! every zmin triangle lies on z = 0 and every zmax one on z = 1
      zerr = 0.0_rk
      do i = 1, m(k)%n_facets
        if (m(k)%facet_group(i) == gz0) zerr = max(zerr, maxval(abs(m(k)%x(m(k)%facet(i, :), 3))))
        if (m(k)%facet_group(i) == gz1) &
          zerr = max(zerr, maxval(abs(m(k)%x(m(k)%facet(i, :), 3) - 1.0_rk)))
      end do
      call check('cube_surface_nodes_'//trim(names(k)), nz0(k) > 0 .and. nz1(k) > 0 .and. &
                 zerr < 1.0e-12_rk, 'zmin '//itoa(nz0(k))//' zmax '//itoa(nz1(k))// &
                 ' max |z error| '//r2s(zerr))
    end do
    same = .true.
    nn = [(m(k)%n_nodes, k = 1, 3)]
    nt = [(m(k)%n_cells, k = 1, 3)]
    do k = 2, 3
      same = same .and. m(k)%n_nodes == m(1)%n_nodes .and. m(k)%n_cells == m(1)%n_cells .and. &
             nz0(k) == nz0(1) .and. nz1(k) == nz1(1) .and. abs(vol(k) - vol(1)) < 1.0e-12_rk
    end do
    call check('cube_formats_agree', same, 'nodes '//ivec(nn)//' tets '//ivec(nt)// &
               ' zmin '//ivec(nz0)//' zmax '//ivec(nz1))
    if (same) then
      call check('cube_connectivity_agree', all(m(1)%cell == m(2)%cell) .and. &
                 all(m(1)%cell == m(3)%cell) .and. all(m(1)%node_tag == m(3)%node_tag) .and. &
                 maxval(abs(m(1)%x - m(2)%x)) < 1.0e-15_rk, 'connectivity or coordinates differ')
    end if

    ! a binary file cut in the middle must be rejected, not misread
    text = read_bytes(trim(tmp_dir)//'/cube_bin.msh')
    call expect_rejected('truncated_binary', 'cube_bin_truncated.msh', text(1:len(text) / 2), '', .true.)
  end subroutine test_cube

end program test_gmsh
