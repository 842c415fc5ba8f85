!> The particles' part of the cycle (issue 15, theory.md section 15):
!> eroded elements of `eroded = 'particles'` materials become particles
!> (their owners send what they were to every rank, which all make the
!> same particles in ascending element id), and every rank advances every
!> particle the same way (SPH among the particles, rigid walls), so the
!> results do not depend on the rank count. The nodes lose the converted
!> elements' mass shares: a node's mass is the sum over its elements that
!> are still elements, in its list's fixed order, whatever the order of
!> the conversions (so a restart recomputes it to the bit).
module udar_particle_driver
  use udar_kinds, only: rk, i8, pi
  use udar_domain, only: domain_t, wall_t
  use udar_config, only: eroded_particles, strength_none, material_cfg_t, geometry_plane_strain, geometry_axisymmetric
  use udar_fracture, only: el_eroded
  use udar_ordering, only: stable_sort_permutation, find_sorted
  use udar_particle_model, only: particles_t, particles_reserve, particles_pair_room
  use udar_sph, only: element_to_particle, particle_pressure, smoothing_length, sph_pairs, sph_forces, sph_rates, &
                      particle_update, particle_strength, wave_speed, artificial_stress, shear_switch, hoop_forces, &
                      axisymmetric_rates
  use udar_comms, only: comms_allgather_count, comms_allgatherv_real, comms_size
  use udar_exact_sum, only: exact_add
  implicit none
  private
  public :: particles_init, particles_convert, particles_forces, particles_move, particles_finish_step, particles_converting, &
            particles_contact_work, particles_onto_planes

  !> smoothing length over the side of the particle's cube (Monaghan 1992: 1.2-1.3)
  real(rk), parameter :: smoothing_factor = 1.2_rk
  !> Monaghan's viscosity (1992): linear and quadratic coefficients
  real(rk), parameter :: visc_alpha = 1.0_rk, visc_beta = 2.0_rk
  !> the particles' critical step over h / v_sig: with the run's dt_safety
  !> (0.9) 0.54 h / v_sig, about 0.27 h / c (Monaghan 1992: 0.3 h / c)
  real(rk), parameter :: critical_share = 0.6_rk
  !> reals a conversion record carries: element id, material, part,
  !> energy, temperature, plastic strain, volume ratio, deviatoric stress
  !> (6), hardening, thermal factor, damage; then per corner the node's id,
  !> its mass share, position and velocity
  integer, parameter :: rec_head = 16, rec_corner = 8
  !> axisymmetric: a particle nearer the axis than this share of its h is
  !> weighted as if it were this far (its radial weight 2 pi r divides its
  !> pair terms: no weight of 0 on the axis itself); every sum takes the
  !> same weight, so the forces' work is still the rates'
  real(rk), parameter :: axis_floor = 0.25_rk

contains

  !> Whether some material's eroded elements become particles.
  pure logical function particles_converting(dom)
    type(domain_t), intent(in) :: dom
    particles_converting = any(dom%mat(:)%eroded == eroded_particles)
  end function

  !> At the start (t = 0 or a restart whose checkpoint gave the particles):
  !> the elements already converted (eroded, of a converting material: a
  !> conversion is made in the cycle of the erosion) and the nodes' masses
  !> without them.
  subroutine particles_init(pt, dom)
    type(particles_t), intent(inout) :: pt
    type(domain_t), intent(inout) :: dom
    integer :: e, n
    pt%enabled = particles_converting(dom)
    if (.not. pt%enabled) return
    ! plane strain: the 2D kernel, with the masses and volumes per metre of
    ! depth; axisymmetric: the 2D kernel on the (r, z) plane, masses per
    ! revolution, the sums those of the area density rho 2 pi r
    pt%axisymmetric = dom%geometry == geometry_axisymmetric
    pt%dim = merge(2, 3, dom%geometry == geometry_plane_strain .or. pt%axisymmetric)
    call particles_reserve(pt, max(pt%n, 1))
    if (allocated(pt%converted)) deallocate(pt%converted)
    allocate(pt%converted(dom%n_elems))
    if (.not. allocated(pt%counts)) allocate(pt%counts(0:comms_size()-1), pt%send(1024))
    do e = 1, dom%n_elems
      pt%converted(e) = dom%el_state(e) == el_eroded .and. dom%mat(dom%el_mat(e))%eroded == eroded_particles
    end do
    if (.not. any(pt%converted)) return
    do n = 1, dom%n_owned_nodes
      call node_mass(dom, pt, n)
    end do
  end subroutine

  !> The owned elements eroded in this cycle whose material converts, to
  !> every rank, and there made particles (collective): mass, momentum and
  !> energy from the element and its corners' shares (element_to_particle),
  !> the element's internal energy then the particle's (the element keeps
  !> none), the nodes' masses without it. n_new: particles made;
  !> dt_nodes: the nodal stable step 2 sqrt(m/k) of the owned nodes that
  !> lost mass (huge if none), which the cycle's step must not exceed.
  !> look: some local element eroded in this cycle (else this rank has
  !> nothing to send and its elements are not scanned).
  subroutine particles_convert(pt, dom, look, n_new, dt_nodes)
    type(particles_t), intent(inout) :: pt
    type(domain_t), intent(inout) :: dom
    logical, intent(in) :: look
    integer, intent(out) :: n_new
    real(rk), intent(out) :: dt_nodes
    integer :: i, e, a, nl, q, r, k, n, first, rec
    integer, allocatable :: perm(:)
    integer(i8), allocatable :: keys(:)
    real(rk), allocatable :: recv(:)
    real(rk) :: m_a(4), x_a(3,4), v_a(3,4), heat
    rec = rec_head + rec_corner*dom%corners
    n_new = 0
    dt_nodes = huge(1.0_rk)
    ! this rank's: owned elements eroded and not yet converted
    nl = 0
    do i = 1, merge(size(dom%el_owned_list), 0, look)
      e = dom%el_owned_list(i)
      if (dom%el_state(e) == el_eroded .and. .not. pt%converted(e) .and. &
          dom%mat(dom%el_mat(e))%eroded == eroded_particles) nl = nl + 1
    end do
    ! (the records' buffer grows when needed: no allocation in a cycle without conversions)
    if (size(pt%send) < rec*nl) then
      deallocate(pt%send)
      allocate(pt%send(2*rec*nl))
    end if
    nl = 0
    do i = 1, merge(size(dom%el_owned_list), 0, look)
      e = dom%el_owned_list(i)
      if (.not. (dom%el_state(e) == el_eroded .and. .not. pt%converted(e) .and. &
          dom%mat(dom%el_mat(e))%eroded == eroded_particles)) cycle
      pt%send(nl+1:nl+rec_head) = [real(dom%el_gidx(e), rk), real(dom%el_mat(e), rk), real(dom%el_part(e), rk), &
                                dom%el_e(e), dom%el_temp(e), dom%el_eps_p(e), dom%el_j(e), dom%el_s(e,:), &
                                dom%el_hard(e), dom%el_soft(e), dom%el_damage(e)]
      do a = 1, dom%corners
        n = dom%el_conn(e,a)
        r = nl + rec_head + rec_corner*(a-1)
        pt%send(r+1:r+rec_corner) = [real(dom%nd_gidx(n), rk), dom%corner_share*dom%el_mass(e), dom%nd_x(:,n), dom%nd_v(:,n)]
      end do
      nl = nl + rec
    end do
    call comms_allgather_count(nl, pt%counts)
    if (sum(pt%counts) == 0) return
    allocate(recv(sum(pt%counts)))
    call comms_allgatherv_real(pt%send(1:nl), pt%counts, recv)
    ! every rank makes them in ascending element id
    n_new = sum(pt%counts)/rec
    allocate(keys(n_new), perm(n_new))
    do k = 1, n_new
      keys(k) = nint(recv(rec*(k-1)+1), i8)
    end do
    call stable_sort_permutation(keys, perm)
    call particles_reserve(pt, pt%n + n_new)
    do k = 1, n_new
      first = rec*(perm(k)-1)
      do a = 1, dom%corners
        r = first + rec_head + rec_corner*(a-1)
        m_a(a) = recv(r+2)
        x_a(:,a) = recv(r+3:r+5)
        v_a(:,a) = recv(r+6:r+8)
      end do
      q = pt%n + 1
      pt%n = q
      pt%elem(q) = nint(recv(first+1))
      pt%mat(q) = nint(recv(first+2))
      pt%part(q) = nint(recv(first+3))
      call element_to_particle(dom%corners, m_a, x_a, v_a, recv(first+4), pt%m(q), pt%x(:,q), pt%v(:,q), pt%e(q), heat)
      pt%heat = pt%heat + heat
      pt%temp(q) = recv(first+5)
      pt%eps_p(q) = recv(first+6)
      ! the density the element's EOS saw
      pt%rho(q) = dom%mat(pt%mat(q))%rho0/recv(first+7)
      ! its strength, unless it had fractured (a fractured element keeps
      ! no deviator; an eroded one of a converting material keeps its own
      ! until here)
      pt%s(:,q) = recv(first+8:first+13)
      pt%hard(q) = recv(first+14)
      pt%soft(q) = recv(first+15)
      pt%damage(q) = recv(first+16)
      pt%strong(q) = dom%mat(pt%mat(q))%strength /= strength_none .and. any(pt%s(:,q) /= 0.0_rk)
      if (pt%axisymmetric) then
        ! (of its area in the (r, z) plane: m / (rho 2 pi r))
        pt%h(q) = smoothing_length(pt%m(q)/(2.0_rk*pi*max(pt%x(1,q), tiny(1.0_rk))), pt%rho(q), smoothing_factor, pt%dim)
      else
        pt%h(q) = smoothing_length(pt%m(q), pt%rho(q), smoothing_factor, pt%dim)
      end if
      call particle_pressure(dom%mat(pt%mat(q)), pt%rho(q), pt%e(q), pt%strong(q), pt%p(q), pt%c(q))
      pt%c(q) = wave_speed(dom%mat(pt%mat(q)), pt%strong(q), pt%rho(q), pt%c(q), pt%p(q), pt%temp(q))
      pt%vsig(q) = 2.0_rk*pt%c(q)
      ! the element, wherever this rank holds it, keeps none of it
      e = find_sorted(dom%el_gidx, pt%elem(q))
      if (e > 0) then
        pt%converted(e) = .true.
        dom%el_e(e) = 0.0_rk
        dom%el_s(e,:) = 0.0_rk
      end if
    end do
    ! a centre behind a symmetry plane (the corners of a wildly distorted
    ! element across it) goes onto the plane
    call particles_onto_planes(pt, dom%sym_walls, pt%n - n_new + 1)
    ! the owned corner nodes' masses without the converted elements
    do k = 1, n_new
      first = rec*(k-1)
      do a = 1, dom%corners
        n = find_sorted(dom%nd_gidx(1:dom%n_owned_nodes), nint(recv(first + rec_head + rec_corner*(a-1) + 1)))
        if (n == 0) cycle
        call node_mass(dom, pt, n)
        if (dom%nd_k(n) > 0.0_rk) dt_nodes = min(dt_nodes, 2.0_rk*sqrt(dom%nd_mass(n)/dom%nd_k(n)))
      end do
    end do
    pt%dt_stable = min(pt%dt_stable, critical_share*minval(pt%h(pt%n-n_new+1:pt%n)/pt%vsig(pt%n-n_new+1:pt%n)))
  end subroutine

  !> Particles first..n found behind a symmetry plane (sym: the planes as
  !> walls, normals into the body) are put on it; their velocities stay.
  !> The planes' wall rule would put them back within one step, at -gap/dt
  !> (11-15 km/s on the Fig. 3 deck, validation.md 4x); particles get
  !> there when made from an element distorted across a plane, or moved by
  !> the contact's returns (which know no symmetry planes).
  subroutine particles_onto_planes(pt, sym, first)
    type(particles_t), intent(inout) :: pt
    type(wall_t), intent(in) :: sym(:)
    integer, intent(in), optional :: first
    integer :: q, i
    do q = merge(first, 1, present(first)), pt%n
      do i = 1, size(sym)
        pt%x(:,q) = pt%x(:,q) - min(dot_product(pt%x(:,q) - sym(i)%point, sym(i)%normal), 0.0_rk)*sym(i)%normal
      end do
    end do
  end subroutine

  !> Owned node n's lumped mass: the shares of its elements not converted,
  !> in its list's order (setup's sum when none is).
  subroutine node_mass(dom, pt, n)
    type(domain_t), intent(inout) :: dom
    type(particles_t), intent(in) :: pt
    integer, intent(in) :: n
    integer :: k
    dom%nd_mass(n) = 0.0_rk
    do k = dom%nd_el_ptr(n), dom%nd_el_ptr(n+1) - 1
      if (pt%converted(dom%nd_el(k))) cycle
      dom%nd_mass(n) = dom%nd_mass(n) + dom%corner_share*dom%el_mass(dom%nd_el(k))
    end do
  end subroutine

  !> The first half of the particles' step, at x(n) with p(n): their mirror
  !> images across the symmetry planes (sym), the pairs (none between two
  !> images), Balsara's switch of the viscosity when asked for, the
  !> artificial stress of the particles that keep their strength (their
  !> material's artificial_stress, mats) and the accelerations (sph_forces);
  !> v(n+1/2) = v(n-1/2) + dt_v a.
  subroutine particles_forces(pt, sym, mats, dt_v)
    type(particles_t), intent(inout) :: pt
    type(wall_t), intent(in) :: sym(:)
    type(material_cfg_t), intent(in) :: mats(:)
    real(rk), intent(in) :: dt_v
    integer :: np, nt, k, q
    if (pt%n == 0) return
    pt%v_prev(:,1:pt%n) = pt%v(:,1:pt%n)
    call make_ghosts(pt, sym)
    nt = pt%n + pt%n_ghosts
    call particles_pair_room(pt, 32*nt)
    do
      call sph_pairs(pt%dim, nt, pt%x, pt%h, 2*nt, pt%cell_start, pt%order, pt%cand, pt%pairs, np)
      if (np >= 0) exit
      call particles_pair_room(pt, 2*size(pt%pairs, 2))
    end do
    ! an image meets only real particles (its own original too)
    if (pt%n_ghosts > 0) then
      nt = 0
      do k = 1, np
        if (pt%pairs(1,k) > pt%n) cycle      ! (i < j: both images)
        nt = nt + 1
        pt%pairs(:,nt) = pt%pairs(:,k)
      end do
      np = nt
    end if
    pt%n_pairs = np
    pt%acc(:,1:pt%n+pt%n_ghosts) = 0
    pt%vsig(1:pt%n+pt%n_ghosts) = 0
    pt%artificial = .false.
    do k = 1, pt%n + pt%n_ghosts
      q = k
      if (k > pt%n) q = pt%ghost_of(k - pt%n)
      pt%art_eps(k) = merge(mats(pt%mat(q))%artificial_stress, 0.0_rk, pt%strong(q))
      pt%artificial = pt%artificial .or. pt%art_eps(k) > 0.0_rk
    end do
    nt = pt%n + pt%n_ghosts
    if (pt%axisymmetric) call radial_weights(pt, nt, pt%x, pt%v, 0.0_rk)
    pt%switch(1:nt) = 1
    if (pt%use_shear_switch) then
      ! (an image's |div v| and |curl v| are its original's)
      if (pt%axisymmetric) then
        call shear_switch(pt%dim, np, pt%pairs, pt%x, pt%v, pt%m, pt%rho, pt%c, pt%h, nt, pt%grad, pt%switch, pt%w)
      else
        call shear_switch(pt%dim, np, pt%pairs, pt%x, pt%v, pt%m, pt%rho, pt%c, pt%h, nt, pt%grad, pt%switch)
      end if
      do k = 1, pt%n_ghosts
        pt%switch(pt%n+k) = pt%switch(pt%ghost_of(k))
      end do
    end if
    ! (2D decks take no artificial stress: the deck sets it 0, theory.md 15)
    if (pt%artificial) call artificial_stress(nt, pt%art_eps, pt%rho, pt%p, pt%s, pt%r_art)
    if (pt%axisymmetric) then
      call sph_forces(pt%dim, visc_alpha, visc_beta, np, pt%pairs, pt%x, pt%v, pt%m, pt%rho, pt%p, pt%c, pt%h, pt%s, pt%visc, &
                      pt%acc, pt%vsig, switch=pt%switch, w=pt%w, gr=pt%gr)
    else if (pt%artificial) then
      call sph_forces(pt%dim, visc_alpha, visc_beta, np, pt%pairs, pt%x, pt%v, pt%m, pt%rho, pt%p, pt%c, pt%h, pt%s, pt%visc, &
                      pt%acc, pt%vsig, pt%r_art, 1.0_rk/smoothing_factor, pt%switch)
    else
      call sph_forces(pt%dim, visc_alpha, visc_beta, np, pt%pairs, pt%x, pt%v, pt%m, pt%rho, pt%p, pt%c, pt%h, pt%s, pt%visc, &
                      pt%acc, pt%vsig, switch=pt%switch)
    end if
    if (pt%axisymmetric) call hoop_forces(pt%n, pt%w, pt%rho, pt%p, pt%s, pt%gr, pt%acc)
    pt%v(:,1:pt%n) = pt%v(:,1:pt%n) + dt_v*pt%acc(:,1:pt%n)
  end subroutine

  !> The images of the particles within 2 max h of a symmetry plane (and
  !> across two planes near their common line, three near a corner), after
  !> the particles in the arrays: position and velocity mirrored, the rest
  !> the original's. A pair of a particle and an image acts on the particle
  !> as the mirrored pair acts on the other: the symmetric half-model's
  !> SPH (momentum normal to a plane is not conserved, energy is).
  subroutine make_ghosts(pt, sym)
    type(particles_t), intent(inout) :: pt
    type(wall_t), intent(in) :: sym(:)
    integer :: i, mask, g, k
    real(rk) :: reach
    logical :: near(size(sym))
    pt%n_ghosts = 0
    if (size(sym) == 0) return
    reach = 0
    do i = 1, pt%n
      reach = max(reach, 2.0_rk*pt%h(i))
    end do
    call particles_reserve(pt, pt%n*2**size(sym))
    g = pt%n
    do i = 1, pt%n
      do k = 1, size(sym)
        near(k) = dot_product(pt%x(:,i) - sym(k)%point, sym(k)%normal) < reach
      end do
      if (.not. any(near)) cycle
      ! every non-empty set of the planes it is near
      do mask = 1, 2**size(sym) - 1
        if (.not. all_near(mask)) cycle
        g = g + 1
        pt%ghost_of(g - pt%n) = i
        pt%ghost_planes(g - pt%n) = mask
        pt%x(:,g) = mirrored(pt%x(:,i), mask, .true.)
        pt%v(:,g) = mirrored(pt%v(:,i), mask, .false.)
        pt%m(g) = pt%m(i); pt%rho(g) = pt%rho(i); pt%p(g) = pt%p(i); pt%c(g) = pt%c(i); pt%h(g) = pt%h(i)
        pt%s(:,g) = mirrored_stress(pt%s(:,i), mask)
      end do
    end do
    pt%n_ghosts = g - pt%n
  contains
    !> Whether the particle is near every plane of mask.
    logical function all_near(mask)
      integer, intent(in) :: mask
      integer :: kk
      all_near = .true.
      do kk = 1, size(sym)
        if (btest(mask, kk-1) .and. .not. near(kk)) all_near = .false.
      end do
    end function
    !> The symmetric tensor s (xx,yy,zz,xy,yz,zx) reflected in the planes
    !> of mask: M s M, M = I - 2 n n^T for each plane.
    function mirrored_stress(s, mask) result(z)
      real(rk), intent(in) :: s(6)
      integer, intent(in) :: mask
      real(rk) :: z(6), a(3,3), mm(3,3)
      integer :: kk, r
      a = reshape([s(1), s(4), s(6), s(4), s(2), s(5), s(6), s(5), s(3)], [3, 3])
      do kk = 1, size(sym)
        if (.not. btest(mask, kk-1)) cycle
        mm = 0
        do r = 1, 3
          mm(r,r) = 1
          mm(:,r) = mm(:,r) - 2.0_rk*sym(kk)%normal*sym(kk)%normal(r)
        end do
        a = matmul(mm, matmul(a, mm))
      end do
      z = [a(1,1), a(2,2), a(3,3), a(1,2), a(2,3), a(3,1)]
    end function
    !> y reflected in the planes of mask (a position, or a velocity: no offset).
    function mirrored(y, mask, position) result(z)
      real(rk), intent(in) :: y(3)
      integer, intent(in) :: mask
      logical, intent(in) :: position
      real(rk) :: z(3), d
      integer :: kk
      z = y
      do kk = 1, size(sym)
        if (.not. btest(mask, kk-1)) cycle
        d = dot_product(z, sym(kk)%normal)
        if (position) d = d - dot_product(sym(kk)%point, sym(kk)%normal)
        z = z - (2.0_rk*d)*sym(kk)%normal
      end do
    end function
  end subroutine

  !> Axisymmetric: the radial weights w = 2 pi r of particles and images
  !> 1..nt at x + tau v (r at least axis_floor h; an image's r is its
  !> original's), and their sums gr cleared for the pair sums.
  subroutine radial_weights(pt, nt, x, v, tau)
    type(particles_t), intent(inout) :: pt
    integer, intent(in) :: nt
    real(rk), intent(in) :: x(:,:), v(:,:), tau
    integer :: k
    do k = 1, nt
      pt%w(k) = 2.0_rk*pi*max(abs(x(1,k) + tau*v(1,k)), axis_floor*pt%h(k))
    end do
    pt%gr(1:nt) = 0
  end subroutine

  !> x(n+1) at v(n+1/2) (after the rigid walls), where the contact pass
  !> finds them; x(n) kept for particles_finish_step.
  subroutine particles_move(pt, dt)
    type(particles_t), intent(inout) :: pt
    real(rk), intent(in) :: dt
    if (pt%n == 0) return
    pt%x_start(:,1:pt%n+pt%n_ghosts) = pt%x(:,1:pt%n+pt%n_ghosts)
    pt%x(:,1:pt%n) = pt%x(:,1:pt%n) + dt*pt%v(:,1:pt%n)
    ! what the contact pass then changes is its work (particles_contact_work)
    pt%v_pre(:,1:pt%n) = pt%v(:,1:pt%n)
  end subroutine

  !> The second half, at the v(n+1/2) the contact pass leaves: the density
  !> and heating rates at the middle of the step (sph_rates, from x(n)), and
  !> the density, energy, pressure and sound speed at n+1 (particle_update,
  !> one material at a time); the particles' critical step. After the
  !> contact, as the elements' stress update is: rates from the velocities
  !> before it, while the kinetic energy ends with those after it, lost
  !> the work of the particles' pressure against the contact's change
  !> (a particle pressed onto a surface and held there heated too little:
  !> -2.5 % of the energy of the long rod at 1.5 km/s, validation.md 4z).
  subroutine particles_finish_step(pt, dom, dt)
    type(particles_t), intent(inout) :: pt
    type(domain_t), intent(in) :: dom
    real(rk), intent(in) :: dt
    integer :: i, j, mt, g, kk
    real(rk) :: d
    if (pt%n == 0) return
    ! the images move as their originals now do
    do g = 1, pt%n_ghosts
      pt%v(:,pt%n+g) = pt%v(:,pt%ghost_of(g))
      do kk = 1, size(dom%sym_walls)
        if (.not. btest(pt%ghost_planes(g), kk-1)) cycle
        d = dot_product(pt%v(:,pt%n+g), dom%sym_walls(kk)%normal)
        pt%v(:,pt%n+g) = pt%v(:,pt%n+g) - (2.0_rk*d)*dom%sym_walls(kk)%normal
      end do
    end do
    pt%drho(1:pt%n+pt%n_ghosts) = 0
    pt%dheat(1:pt%n+pt%n_ghosts) = 0
    ! (axisymmetric: the weights and radial sums at the middle of the step, where the rates take the kernel)
    if (pt%axisymmetric) call radial_weights(pt, pt%n + pt%n_ghosts, pt%x_start, pt%v, 0.5_rk*dt)
    if (pt%artificial) then
      pt%grad(:,1:pt%n+pt%n_ghosts) = 0
      call sph_rates(pt%dim, dt, pt%n_pairs, pt%pairs, pt%x_start, pt%v, pt%m, pt%h, pt%visc, pt%drho, pt%dheat, pt%grad, &
                     pt%r_art, 1.0_rk/smoothing_factor)
    else if (any(pt%strong(1:pt%n)) .or. pt%axisymmetric) then
      pt%grad(:,1:pt%n+pt%n_ghosts) = 0
      if (pt%axisymmetric) then
        call sph_rates(pt%dim, dt, pt%n_pairs, pt%pairs, pt%x_start, pt%v, pt%m, pt%h, pt%visc, pt%drho, pt%dheat, pt%grad, &
                       gr=pt%gr)
      else
        call sph_rates(pt%dim, dt, pt%n_pairs, pt%pairs, pt%x_start, pt%v, pt%m, pt%h, pt%visc, pt%drho, pt%dheat, pt%grad)
      end if
    else
      call sph_rates(pt%dim, dt, pt%n_pairs, pt%pairs, pt%x_start, pt%v, pt%m, pt%h, pt%visc, pt%drho, pt%dheat)
    end if
    if (pt%axisymmetric) call axisymmetric_rates(pt%n, pt%w, pt%rho, pt%v, pt%gr, pt%drho, pt%grad)
    ! each run of particles of one material together (the kernel takes one)
    i = 1
    do while (i <= pt%n)
      mt = pt%mat(i)
      j = i
      do while (j < pt%n)
        if (pt%mat(j+1) /= mt) exit
        j = j + 1
      end do
      ! the deviator first, with the density of step n (its work joins the heating)
      call particle_strength(dom%mat(mt), j - i + 1, dt, pt%rho(i:j), pt%grad(:,i:j), pt%p(i:j), pt%strong(i:j), &
                             pt%s(:,i:j), pt%eps_p(i:j), pt%hard(i:j), pt%soft(i:j), pt%temp(i:j), pt%damage(i:j), &
                             pt%dheat(i:j))
      call particle_update(dom%mat(mt), j - i + 1, dt, pt%m(i:j), pt%drho(i:j), pt%dheat(i:j), pt%strong(i:j), &
                           pt%temp(i:j), pt%rho(i:j), pt%e(i:j), pt%p(i:j), pt%c(i:j))
      i = j + 1
    end do
    pt%dt_stable = huge(1.0_rk)
    do i = 1, pt%n
      pt%dt_stable = min(pt%dt_stable, critical_share*pt%h(i)/max(pt%vsig(i), 2.0_rk*pt%c(i)))
    end do
  end subroutine

  !> The contact pass's work on the particles into the exact accumulator
  !> acc, as contact_work books the nodes': m dv . (v(n-1/2) + v(n+1/2))/2
  !> (the caller adds it on one rank: every rank has every particle).
  subroutine particles_contact_work(pt, acc)
    type(particles_t), intent(in) :: pt
    integer(i8), intent(inout) :: acc(0:)
    integer :: q
    real(rk) :: dv(3)
    do q = 1, pt%n
      dv = pt%v(:,q) - pt%v_pre(:,q)
      if (all(dv == 0.0_rk)) cycle
      call exact_add(acc, 0.5_rk*pt%m(q)*dot_product(dv, pt%v_prev(:,q) + pt%v(:,q)))
    end do
  end subroutine

end module udar_particle_driver
