!> Unit test of udar_partition: structured tet cubes (6 Kuhn tets per cube)
!> and a two-body mesh. Args <tests/unit dir> <work dir> are accepted and unused.
program test_partition
  use udar_kinds, only: rk
  use udar_partition, only: partition_elements, partition_stats_t, metis_idx_width_ok
  implicit none

  integer :: n_fail = 0
  integer, allocatable :: cube(:,:), two(:,:), small(:,:), isol(:,:)
  integer :: n_cube_nodes, n_two_nodes, n_small_nodes, n_isol_nodes

  call check(metis_idx_width_ok(), 'metis_idx_width_ok', 'METIS idx_t/real_t is not 32-bit')

  call cube_mesh(8, 0, cube, n_cube_nodes)
  call two_body_mesh(two, n_two_nodes)
  call cube_mesh(2, 0, small, n_small_nodes)
  call isolated_tets(3, isol, n_isol_nodes)

  call check_mesh('cube8', n_cube_nodes, cube, 1, .true.)
  call check_mesh('two_body', n_two_nodes, two, 2, .true.)
  call check_single_part()
  call check_weights()
  call check_many_parts()
  call check_small_sweep()
  call check_isolated()
  call check_errors()

  if (n_fail > 0) then
    write (*, '(i0,a)') n_fail, ' check(s) failed'
    error stop 1
  end if
  write (*, '(a)') 'all partition checks passed'

contains

  subroutine check(cond, name, detail)
    logical, intent(in) :: cond
    character(len=*), intent(in) :: name, detail
    if (cond) then
      write (*, '(a)') 'PASS '//name
    else
      write (*, '(a)') 'FAIL '//name//': '//detail
      n_fail = n_fail + 1
    end if
  end subroutine

  !> n^3 cubes of 6 tets each (Kuhn split along the main diagonal: conforming),
  !> node numbers offset by node0.
  subroutine cube_mesh(n, node0, conn, n_nodes)
    integer, intent(in) :: n, node0
    integer, allocatable, intent(out) :: conn(:,:)
    integer, intent(out) :: n_nodes
    integer, parameter :: perms(3,6) = reshape([1,2,3, 1,3,2, 2,1,3, 2,3,1, 3,1,2, 3,2,1], [3,6])
    integer :: i, j, k, p, s, e, c(3)
    n_nodes = (n + 1)**3
    allocate(conn(6*n**3, 4))
    e = 0
    do k = 0, n - 1
      do j = 0, n - 1
        do i = 0, n - 1
          do p = 1, 6
            e = e + 1
            c = [i, j, k]
            conn(e, 1) = node0 + 1 + c(1) + (n + 1)*(c(2) + (n + 1)*c(3))
            do s = 1, 3
              c(perms(s, p)) = c(perms(s, p)) + 1
              conn(e, s + 1) = node0 + 1 + c(1) + (n + 1)*(c(2) + (n + 1)*c(3))
            end do
          end do
        end do
      end do
    end do
  end subroutine

  !> Plate (8^3 cubes) followed by a separate projectile (4^3 cubes).
  subroutine two_body_mesh(conn, n_nodes)
    integer, allocatable, intent(out) :: conn(:,:)
    integer, intent(out) :: n_nodes
    integer, allocatable :: a(:,:), b(:,:)
    integer :: na, nb
    call cube_mesh(8, 0, a, na)
    call cube_mesh(4, na, b, nb)
    n_nodes = na + nb
    allocate(conn(size(a, 1) + size(b, 1), 4))
    conn(1:size(a, 1), :) = a
    conn(size(a, 1) + 1:, :) = b
  end subroutine

  !> n tets sharing no node.
  subroutine isolated_tets(n, conn, n_nodes)
    integer, intent(in) :: n
    integer, allocatable, intent(out) :: conn(:,:)
    integer, intent(out) :: n_nodes
    integer :: e
    allocate(conn(n, 4))
    do e = 1, n
      conn(e, :) = [4*e - 3, 4*e - 2, 4*e - 1, 4*e]
    end do
    n_nodes = 4*n
  end subroutine

  !> Face neighbours found independently of the module: elements sharing 3 nodes.
  subroutine dual_by_nodes(n_nodes, conn, nbr, n_nbr)
    integer, intent(in) :: n_nodes, conn(:,:)
    integer, allocatable, intent(out) :: nbr(:,:)
    integer, allocatable, intent(out) :: n_nbr(:)
    integer, allocatable :: cnt(:), start(:), list(:), fill(:)
    integer :: ne, e, f, j, jj, t
    ne = size(conn, 1)
    allocate(cnt(n_nodes), source=0)
    do e = 1, ne
      cnt(conn(e, :)) = cnt(conn(e, :)) + 1
    end do
    allocate(start(n_nodes + 1))
    start(1) = 1
    do j = 1, n_nodes
      start(j + 1) = start(j) + cnt(j)
    end do
    allocate(list(start(n_nodes + 1) - 1), fill(n_nodes))
    fill = start(1:n_nodes)
    do e = 1, ne
      do j = 1, 4
        list(fill(conn(e, j))) = e
        fill(conn(e, j)) = fill(conn(e, j)) + 1
      end do
    end do
    allocate(nbr(8, ne), n_nbr(ne), source=0)
    do e = 1, ne
      do j = 1, 4
        do t = start(conn(e, j)), start(conn(e, j) + 1) - 1
          f = list(t)
          if (f == e) cycle
          if (any(nbr(1:n_nbr(e), e) == f)) cycle
          if (count([(any(conn(f, :) == conn(e, jj)), jj = 1, 4)]) == 3) then
            n_nbr(e) = n_nbr(e) + 1
            nbr(n_nbr(e), e) = f
          end if
        end do
      end do
    end do
  end subroutine

  !> Number of face-connected pieces of part p.
  integer function n_pieces(part, p, nbr, n_nbr)
    integer, intent(in) :: part(:), p, nbr(:,:), n_nbr(:)
    logical, allocatable :: seen(:)
    integer, allocatable :: q(:)
    integer :: s, head, tail, v, k, w
    allocate(seen(size(part)), source=.false.)
    allocate(q(size(part)))
    n_pieces = 0
    do s = 1, size(part)
      if (seen(s) .or. part(s) /= p) cycle
      n_pieces = n_pieces + 1
      seen(s) = .true.
      head = 1; tail = 1; q(1) = s
      do while (head <= tail)
        v = q(head); head = head + 1
        do k = 1, n_nbr(v)
          w = nbr(k, v)
          if (.not. seen(w) .and. part(w) == p) then
            seen(w) = .true.
            tail = tail + 1; q(tail) = w
          end if
        end do
      end do
    end do
  end function

  !> Range, sizes, balance, edge cut, determinism and contiguity for 2, 3, 4, 7 parts.
  subroutine check_mesh(name, n_nodes, conn, n_bodies, check_contig)
    character(len=*), intent(in) :: name
    integer, intent(in) :: n_nodes, conn(:,:), n_bodies
    logical, intent(in) :: check_contig
    integer, parameter :: nps(4) = [2, 3, 4, 7]
    integer, allocatable :: part(:), part2(:), nbr(:,:), n_nbr(:), sizes(:)
    type(partition_stats_t) :: st, st2
    logical :: ok, ok2
    character(len=:), allocatable :: msg, msg2
    character(len=200) :: d
    character(len=64) :: tag
    integer :: ip, np, ne, e, k, cut, p, worst
    ne = size(conn, 1)
    call dual_by_nodes(n_nodes, conn, nbr, n_nbr)
    allocate(part(ne), part2(ne))
    do ip = 1, size(nps)
      np = nps(ip)
      write (tag, '(a,a,i0)') name, ' np=', np
      call partition_elements(n_nodes, conn, np, part, st, ok, msg)
      call check(ok, trim(tag)//' ok', msg)
      if (.not. ok) cycle
      call check(all(part >= 0 .and. part < np), trim(tag)//' range', 'part number out of range')
      allocate(sizes(0:np - 1), source=0)
      do e = 1, ne
        sizes(part(e)) = sizes(part(e)) + 1
      end do
      write (d, '(a,i0,a,i0)') 'sum ', sum(st%part_size), ' /= ', ne
      call check(sum(st%part_size) == ne .and. all(sizes == st%part_size) .and. st%n_parts == np, &
                 trim(tag)//' sizes', d)
      write (d, '(a,f8.4,a,*(i0,:,","))') 'imbalance ', st%imbalance, ' sizes ', st%part_size
      write (*, '(a)') '  info '//trim(tag)//': '//trim(d)
      call check(st%imbalance <= 1.05_rk .and. &
                 abs(st%imbalance - real(maxval(sizes)*np, rk)/real(ne, rk)) < 1.0e-12_rk, &
                 trim(tag)//' imbalance', d)
      cut = 0
      do e = 1, ne
        do k = 1, n_nbr(e)
          if (nbr(k, e) > e .and. part(nbr(k, e)) /= part(e)) cut = cut + 1
        end do
      end do
      write (d, '(a,i0,a,i0)') 'stats ', st%edge_cut, ' recount ', cut
      write (*, '(a,i0)') '  info '//trim(tag)//': edge cut ', cut
      call check(cut == st%edge_cut, trim(tag)//' edge_cut', d)
      call partition_elements(n_nodes, conn, np, part2, st2, ok2, msg2)
      call check(ok2 .and. all(part2 == part) .and. st2%edge_cut == st%edge_cut .and. &
                 all(st2%part_size == st%part_size), trim(tag)//' deterministic', 'second call differs')
      if (check_contig) then
        ! every part is one piece per body it touches (one piece on a single body)
        worst = 0
        do p = 0, np - 1
          worst = max(worst, n_pieces(part, p, nbr, n_nbr))
        end do
        write (d, '(a,i0,a)') 'a part has ', worst, ' face-connected pieces'
        call check(worst <= n_bodies, trim(tag)//' contiguous', d)
      end if
      deallocate(sizes)
    end do
  end subroutine

  subroutine check_single_part()
    integer, allocatable :: part(:)
    type(partition_stats_t) :: st
    logical :: ok
    character(len=:), allocatable :: msg
    allocate(part(size(cube, 1)), source=-1)
    call partition_elements(n_cube_nodes, cube, 1, part, st, ok, msg)
    call check(ok .and. all(part == 0) .and. st%n_parts == 1 .and. st%edge_cut == 0 .and. &
               all(st%part_size == [size(cube, 1)]) .and. abs(st%imbalance - 1) < 1.0e-12_rk, &
               'n_parts=1', 'not a single part with zero cut')
  end subroutine

  !> Vertex weights (the elements' cost): the first half of the cube's
  !> elements weighs 3, the rest 1. Two parts then balance the weights, not
  !> the counts: the part holding more heavy elements holds fewer elements.
  !> Weights < 1 are refused.
  subroutine check_weights()
    integer, allocatable :: part(:), w(:)
    type(partition_stats_t) :: st
    logical :: ok
    character(len=:), allocatable :: msg
    character(len=200) :: detail
    integer :: ne, heavy_part
    ne = size(cube, 1)
    allocate(part(ne), w(ne))
    w = 1
    w(1:ne/2) = 3
    call partition_elements(n_cube_nodes, cube, 2, part, st, ok, msg, w)
    call check(ok, 'weights ok', msg)
    if (.not. ok) return
    ! the part holding more of the heavy elements
    heavy_part = merge(0, 1, count(part == 0 .and. w == 3) > count(part == 1 .and. w == 3))
    write (detail, '(a,f6.3,a,f6.3,a,2i6)') 'weighted imbalance ', st%weighted_imbalance, ', count imbalance ', &
      st%imbalance, ', part sizes ', st%part_size
    call check(st%weighted_imbalance < 1.05_rk .and. st%imbalance > 1.15_rk .and. &
               st%part_size(heavy_part) < st%part_size(1 - heavy_part), 'weights balanced', trim(detail))
    write (*, '(a)') 'MEASURED '//trim(detail)
    w(1) = 0
    call partition_elements(n_cube_nodes, cube, 2, part, st, ok, msg, w)
    call check(.not. ok .and. index(msg, 'weights must be >= 1') > 0, 'weights below 1 refused', msg)
  end subroutine

  !> More parts than elements: one element per part, the rest empty.
  subroutine check_many_parts()
    integer, allocatable :: part(:)
    type(partition_stats_t) :: st
    logical :: ok
    character(len=:), allocatable :: msg
    integer :: ne, e
    ne = 48
    allocate(part(ne))
    call partition_elements(n_small_nodes, small, 100, part, st, ok, msg)
    call check(ok, 'n_parts>n_elems ok', msg)
    if (.not. ok) return
    call check(all(part >= 0 .and. part < 100) .and. sum(st%part_size) == ne .and. &
               size(st%part_size) == 100 .and. count(st%part_size == 0) == 100 - ne .and. &
               maxval(st%part_size) == 1 .and. all(part == [(e - 1, e = 1, ne)]), &
               'n_parts>n_elems parts', 'expected one element in each of the first parts')
    call check(abs(st%imbalance - 100.0_rk/ne) < 1.0e-12_rk, 'n_parts>n_elems imbalance', &
               'imbalance is not n_parts/n_elems')
    call partition_elements(n_small_nodes, small, ne, part, st, ok, msg)
    call check(ok .and. all(st%part_size == 1), 'n_parts=n_elems', 'not one element per part')
  end subroutine

  !> METIS near its limits: every part count 2..n_elems-1 on 48 elements.
  subroutine check_small_sweep()
    integer, allocatable :: part(:)
    type(partition_stats_t) :: st
    logical :: ok, all_ok
    character(len=:), allocatable :: msg
    character(len=200) :: d
    integer :: np, ne
    ne = size(small, 1)
    allocate(part(ne))
    all_ok = .true.
    d = ''
    do np = 2, ne - 1
      call partition_elements(n_small_nodes, small, np, part, st, ok, msg)
      if (.not. ok) then
        all_ok = .false.; write (d, '(a,i0,a)') 'np=', np, ': '//msg; exit
      end if
      if (any(part < 0 .or. part >= np) .or. sum(st%part_size) /= ne) then
        all_ok = .false.; write (d, '(a,i0,a)') 'np=', np, ': bad parts'; exit
      end if
    end do
    call check(all_ok, 'small mesh np=2..47', d)
  end subroutine

  !> Elements with no face neighbours at all (3 disconnected tets, 2 parts).
  subroutine check_isolated()
    integer, allocatable :: part(:)
    type(partition_stats_t) :: st
    logical :: ok
    character(len=:), allocatable :: msg
    allocate(part(size(isol, 1)))
    call partition_elements(n_isol_nodes, isol, 2, part, st, ok, msg)
    call check(ok, 'isolated tets ok', msg)
    if (.not. ok) return
    call check(all(part >= 0 .and. part < 2) .and. sum(st%part_size) == 3 .and. st%edge_cut == 0, &
               'isolated tets parts', 'bad parts or non-zero cut')
  end subroutine

  subroutine check_errors()
    integer, allocatable :: part(:), bad(:,:)
    type(partition_stats_t) :: st
    logical :: ok
    character(len=:), allocatable :: msg
    allocate(part(size(small, 1)))
    call partition_elements(n_small_nodes, small, 0, part, st, ok, msg)
    call check(.not. ok .and. len(msg) > 0, 'n_parts=0 rejected', 'accepted')
    bad = small
    bad(5, 2) = n_small_nodes + 1
    call partition_elements(n_small_nodes, bad, 2, part, st, ok, msg)
    call check(.not. ok .and. len(msg) > 0, 'bad node index rejected', 'accepted')
  end subroutine

end program test_partition
