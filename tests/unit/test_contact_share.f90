!> Unit test of the contact search's shares (udar_contact_model
!> assign_slaves): on 1 to 7 ranks every slave node is searched by exactly
!> one rank, the ranks' shares differ by one node at most, every rank's
!> view of who searches what (searcher) is the same, and a share is
!> compact in space (Morton runs): on 4 ranks of a plane grid of nodes
!> each share's box covers well under the whole grid.
program test_contact_share
  use udar_kinds, only: rk
  use udar_contact_model, only: interface_t, assign_slaves
  use unit_checks, only: check, check_summary
  implicit none
  integer, parameter :: nx = 23, ny = 17
  real(rk) :: x0(3, nx*ny), lo(3), hi(3), area_max
  type(interface_t) :: it
  integer :: np, r, i, j, counts(0:6), reference(nx*ny)
  logical :: once, same
  character(len=120) :: detail
  do j = 1, ny
    do i = 1, nx
      x0(:, i + nx*(j - 1)) = [0.001_rk*i, 0.002_rk*j, 0.0_rk]
    end do
  end do
  ! the slave list in an order unlike space (every third node first)
  it%slave = [(i, i = 1, nx*ny, 3), (i, i = 2, nx*ny, 3), (i, i = 3, nx*ny, 3)]
  once = .true.
  same = .true.
  do np = 1, 7
    counts = 0
    do r = 0, np - 1
      call assign_slaves(it, x0, r, np)
      counts(r) = count(it%mine)
      if (r == 0) reference = it%searcher
      same = same .and. all(it%searcher == reference) .and. all(it%mine .eqv. (it%searcher == r))
    end do
    once = once .and. sum(counts(0:np-1)) == nx*ny .and. maxval(counts(0:np-1)) - minval(counts(0:np-1)) <= 1
  end do
  call check('contact_share_each_node_once_balanced', once, 'every slave node in one share; shares within one node')
  call check('contact_share_same_on_every_rank', same, 'searcher(k) the same from every rank''s call')
  area_max = 0
  do r = 0, 3
    call assign_slaves(it, x0, r, 4)
    lo = minval(x0(:, pack(it%slave, it%mine)), dim=2)
    hi = maxval(x0(:, pack(it%slave, it%mine)), dim=2)
    area_max = max(area_max, (hi(1) - lo(1))*(hi(2) - lo(2)))
  end do
  area_max = area_max/((0.001_rk*(nx - 1))*(0.002_rk*(ny - 1)))
  write(detail, '(a,f6.3,a)') 'largest share''s box on 4 ranks: ', area_max, ' of the grid''s area (bound 0.75; 1 for shares not compact)'
  call check('contact_share_compact', area_max < 0.75_rk, trim(detail))
  call check_summary()
end program test_contact_share
