!> Closed voids (&contact voids): the hole an eroded tetrahedron leaves in
!> an eroding part of a contact may close but not turn inside out. Erosion
!> frees the faces around the hole, and without this the nodes across it
!> pass through each other: the eroding body folds into itself (a crater
!> lip through the plate element beside it), and whatever slides on the
!> fold goes in with it, where no node-on-face contact can take it out
!> (validation.md 4ze, 4zi). The eroded element's signed volume V(x)
!> stays >= 0: where it is negative and still closing (dV/dt < 0), its
!> corners' velocities lose the closing rate along the volume's gradient,
!> over their masses (a perfectly inelastic constraint, as the contact's
!> velocity matching is), positions moving with the change over the step.
!> The gradient of V sums to zero and V is invariant under rotation, so
!> momentum and angular momentum are exact; symmetry planes and fixed
!> nodes take part through the constrained inverse mass (a node on a
!> plane moves only in it). Parallel: every rank corrects its local voids
!> from the same current state (ghosts fresh from a halo exchange just
!> before) and each owned node sums its voids' changes in ascending
!> element id, so results are bitwise independent of the partition.
module udar_eroded_voids
  use udar_kinds, only: rk, i8
  use udar_domain, only: domain_t
  use udar_fracture, only: el_eroded
  use udar_vectors, only: cross
  use udar_contact_search, only: ensure
  use udar_comms, only: halo_t, comms_halo_exchange, comms_halo_exchange_scalar
  implicit none
  private
  !> sweeps of the voids a cycle (each a halo exchange on more than one rank)
  integer, parameter :: void_sweeps = 3
  public :: voids_t, voids_setup, voids_enforce, void_changes, volume_gradients, voids_mark_stale

  type :: voids_t
    logical :: on = .false.
    logical, allocatable :: part_on(:)       !< parts whose eroded elements are closed voids
    logical :: stale = .true.                !< the list of voids needs rebuilding (erosion since)
    integer, allocatable :: list(:)          !< local eroded elements of those parts, ascending (1:n_list)
    integer :: n_list = 0
    real(rk), allocatable :: proj(:,:,:)     !< (3,3,local nodes) the velocity conditions' projector
    real(rk), allocatable :: dv(:)           !< work: each held void's corner velocity changes, 12 a void
    integer, allocatable :: slot(:)          !< (local elements) work: the void's row in dv, 0 none
    logical, allocatable :: touched(:)       !< (local nodes) work
    integer, allocatable :: nodes(:)         !< work: the owned nodes touched
    integer, allocatable :: held(:)          !< work: the voids held in a sweep
    real(rk), allocatable :: share(:)        !< (local nodes) work: the held voids at each node
    integer :: held_cycle = 0                !< voids held this cycle (on this rank, owned elements)
    integer(i8) :: held_total = 0            !< over the run
  end type

contains

  !> parts(k): part k's eroded elements are closed voids (the deck's
  !> eroding parts of contacts with voids = .true.); the projector of the
  !> velocity conditions at every local node (identity, less each symmetry
  !> plane's normal; zero at a fixed node).
  subroutine voids_setup(vd, dom, parts)
    type(voids_t), intent(inout) :: vd
    type(domain_t), intent(in) :: dom
    logical, intent(in) :: parts(:)
    integer :: k, n, a
    real(rk) :: pn(3), q
    vd%on = any(parts)
    if (.not. vd%on) return
    vd%part_on = parts
    vd%stale = .true.
    ! the list's room: every local element of those parts; the work rows
    ! grow by half again as voids are held (ensure: a few times a run)
    allocate(vd%list(count(parts(dom%el_part(1:dom%n_elems)))), vd%dv(12*16), vd%nodes(64), vd%held(16), &
             vd%share(dom%n_nodes))
    vd%n_list = 0
    allocate(vd%proj(3,3,dom%n_nodes), vd%slot(dom%n_elems), vd%touched(dom%n_nodes))
    vd%slot = 0
    vd%touched = .false.
    vd%proj = 0
    do n = 1, dom%n_nodes
      do a = 1, 3
        vd%proj(a,a,n) = 1
      end do
    end do
    do k = 1, size(dom%sym_nodes)
      n = dom%sym_nodes(k)
      pn = matmul(vd%proj(:,:,n), dom%sym_normal(k,:))
      q = dot_product(pn, pn)
      if (q <= 0.0_rk) cycle
      do a = 1, 3
        vd%proj(:,a,n) = vd%proj(:,a,n) - pn*pn(a)/q
      end do
    end do
    do k = 1, size(dom%fixed_nodes)
      vd%proj(:,:,dom%fixed_nodes(k)) = 0
    end do
  end subroutine

  !> Erosion happened: the list of voids is rebuilt before the next pass.
  subroutine voids_mark_stale(vd)
    type(voids_t), intent(inout) :: vd
    vd%stale = .true.
  end subroutine

  !> The velocity changes dv(:,a) of the corners x(:,a) (velocities v,
  !> masses m, velocity-condition projectors p) of a void (an eroded
  !> tetrahedron) whose signed volume V is negative and decreasing, that
  !> stop its decrease:
  !>   dv_a = -lambda P_a g_a / m_a,  lambda = (sum g_a.v_a) / w,  w = sum g_a.P_a g_a / m_a,
  !> g_a = dV/dx_a: after them dV/dt = sum g_a.(v_a + dv_a) = 0, and the
  !> kinetic energy lost is lambda^2 w / 2 (a perfectly inelastic
  !> constraint). held false (no change): V >= 0, V not decreasing, a
  !> corner without mass (m <= 0), or no corner free to move (w = 0).
  !> Positions are not returned: a return without a velocity would change
  !> the elements' energy unbooked (tried with returns of up to 0.05 of the
  !> void's size a step: the Fig. 4 deck's energy error 4 times larger).
  pure subroutine void_changes(x, v, m, p, dv, held)
    real(rk), intent(in) :: x(3,4), v(3,4), m(4), p(3,3,4)
    real(rk), intent(out) :: dv(3,4)
    logical, intent(out) :: held
    real(rk) :: g(3,4), pg(3,4), vol, rate, w, lambda
    integer :: a
    dv = 0
    held = .false.
    if (any(m <= 0.0_rk)) return
    call volume_gradients(x, g, vol)
    if (vol >= 0.0_rk) return
    rate = 0
    w = 0
    do a = 1, 4
      rate = rate + dot_product(g(:,a), v(:,a))
      pg(:,a) = matmul(p(:,:,a), g(:,a))
      w = w + dot_product(g(:,a), pg(:,a))/m(a)
    end do
    if (rate >= 0.0_rk .or. w <= 0.0_rk) return
    lambda = rate/w
    do a = 1, 4
      dv(:,a) = -lambda*pg(:,a)/m(a)
    end do
    held = .true.
  end subroutine

  !> The gradients g(:,a) = dV/dx_a of a tetrahedron's signed volume V at
  !> corners x (sum_a g_a = 0; V = (x_2 - x_1).g_2).
  pure subroutine volume_gradients(x, g, vol)
    real(rk), intent(in) :: x(3,4)
    real(rk), intent(out) :: g(3,4), vol
    g(:,2) = cross(x(:,3) - x(:,1), x(:,4) - x(:,1))/6.0_rk
    g(:,3) = cross(x(:,4) - x(:,1), x(:,2) - x(:,1))/6.0_rk
    g(:,4) = cross(x(:,2) - x(:,1), x(:,3) - x(:,1))/6.0_rk
    g(:,1) = -(g(:,2) + g(:,3) + g(:,4))
    vol = dot_product(x(:,2) - x(:,1), g(:,2))
  end subroutine

  !> Holds the voids of this step at x(n+1) with v(n+1/2), in void_sweeps
  !> sweeps. In each, every local void is held or not from the current
  !> state of its corners (ghosts current: the caller's halo exchange
  !> before the first sweep, this routine's before the others), each node
  !> counts the held voids at it (owned nodes over their complete element
  !> lists, ghosts from their owners), and each held void acts on its
  !> share of its corners' masses, m_a / n_a (mass splitting, Tonge,
  !> Benevolenskiy and Voroshilov 2012): a node's change is the mean of its shares', so a sweep
  !> never adds kinetic energy where voids share nodes (each share loses
  !> energy, and the mean of the shares' velocities has at most their mean
  !> energy), which summing the voids' own changes would. Each owned node
  !> sums its voids' changes in ascending element id; positions move with
  !> the change over the step.
  subroutine voids_enforce(vd, dom, halo, dt)
    type(voids_t), intent(inout) :: vd
    type(domain_t), intent(inout) :: dom
    type(halo_t), intent(inout) :: halo
    real(rk), intent(in) :: dt
    real(rk) :: xe(3,4), ve(3,4), me(4), pe(3,3,4), dv(3,4), acc(3)
    integer :: k, e, c, n, nv, nn, j, s, sweep
    logical :: held
    if (.not. vd%on) return
    if (vd%stale) call rebuild_list()
    vd%held_cycle = 0
    do sweep = 1, void_sweeps
      if (sweep > 1) call comms_halo_exchange(halo, dom%nd_x, dom%nd_v)
      ! the voids held in this sweep, and each node's count of them
      vd%share = 0
      nv = 0
      do k = 1, vd%n_list
        e = vd%list(k)
        call gather(e, .false.)
        call void_changes(xe, ve, me, pe, dv, held)
        if (.not. held) cycle
        nv = nv + 1
        call ensure(vd%held, nv, keep=.true.)
        vd%held(nv) = e
        do c = 1, 4
          n = dom%el_conn(e,c)
          if (n <= dom%n_owned_nodes) vd%share(n) = vd%share(n) + 1
        end do
        if (sweep == 1 .and. dom%el_owned(e)) vd%held_cycle = vd%held_cycle + 1
      end do
      call comms_halo_exchange_scalar(halo, vd%share)
      ! each held void on its share of its corners' masses
      nn = 0
      do k = 1, nv
        e = vd%held(k)
        call gather(e, .true.)
        call void_changes(xe, ve, me, pe, dv, held)
        call ensure(vd%dv, 12*k, keep=.true.)
        vd%dv(12*k-11:12*k) = reshape(dv, [12])
        vd%slot(e) = k
        do c = 1, 4
          n = dom%el_conn(e,c)
          if (n > dom%n_owned_nodes .or. vd%touched(n)) cycle
          vd%touched(n) = .true.
          nn = nn + 1
          call ensure(vd%nodes, nn, keep=.true.)
          vd%nodes(nn) = n
        end do
      end do
      ! each owned node: the mean of its shares' changes, in ascending element id
      do j = 1, nn
        n = vd%nodes(j)
        acc = 0
        do k = dom%nd_el_ptr(n), dom%nd_el_ptr(n+1) - 1
          e = dom%nd_el(k)
          s = vd%slot(e)
          if (s == 0) cycle
          c = 12*(s - 1) + 3*(dom%nd_el_corner(k) - 1)
          acc = acc + vd%dv(c+1:c+3)
        end do
        acc = acc/vd%share(n)
        dom%nd_v(:,n) = dom%nd_v(:,n) + acc
        dom%nd_x(:,n) = dom%nd_x(:,n) + dt*acc
        vd%touched(n) = .false.
      end do
      do k = 1, nv
        vd%slot(vd%held(k)) = 0
      end do
    end do
    vd%held_total = vd%held_total + vd%held_cycle

  contains

    !> Void e's corners: their whole masses, or (shares) their shares m_a / n_a.
    subroutine gather(e, shares)
      integer, intent(in) :: e
      logical, intent(in) :: shares
      integer :: cc, nc
      do cc = 1, 4
        nc = dom%el_conn(e,cc)
        xe(:,cc) = dom%nd_x(:,nc)
        ve(:,cc) = dom%nd_v(:,nc)
        me(cc) = dom%nd_mass(nc)
        if (shares) me(cc) = me(cc)/vd%share(nc)
        pe(:,:,cc) = vd%proj(:,:,nc)
      end do
    end subroutine

    subroutine rebuild_list()
      integer :: ee
      vd%n_list = 0
      do ee = 1, dom%n_elems
        if (dom%el_state(ee) /= el_eroded) cycle
        if (.not. vd%part_on(dom%el_part(ee))) cycle
        vd%n_list = vd%n_list + 1
        vd%list(vd%n_list) = ee
      end do
      vd%stale = .false.
    end subroutine
  end subroutine
end module udar_eroded_voids
