!> The material half of an element pass, shared by the drivers of every
!> element kind (3D tet4: udar_element_driver; 2D tri3: udar_tri_driver).
!> A driver fills a block's volumes, smallest altitudes and strain rates
!> (element_block_t vol, h, d, w: the 3D ordering, 2D rates in the places
!> of xx, yy, zz, xy as theory.md section 14 says), then:
!>   block_volume_ratios  the volume ratio the EOS sees (nodal average or own)
!>   material_update      strength, EOS and viscosity (bulk, visc)
!>   (its stiffness bound into lam)
!>   material_finish      own step, heating, fracture, erosion, state kept,
!>                        the pressures its forces and its nodes take
!>   (its forces, added to the nodes in ascending element id)
!>   block_nodes_done     the nodal pressures and the nodal time step of the
!>                        nodes whose element lists the block completed
!> So both dimensions have one stress update, one fracture and one erosion.
!> Also the passes over nodes that any element kind shares (nodal reference
!> volumes and pressures, the nodal time step) and the elements' measured
!> cost.
module udar_element_shared
  use udar_kinds, only: rk, i8
  use udar_domain, only: domain_t, block_size
  use udar_strength, only: strength_block, thermal_softening_update, von_mises
  use udar_fracture, only: el_fractured, el_eroded, el_intact, erode_strain, erode_time_step, erode_inverted, &
                           erode_converted, erode_reasons, &
      fracture_update, fracture_enabled, erosion_enabled, deviatoric_rate
  use udar_hydro, only: volumetric_update, blended_volume_ratios, blended_pressures, shock_heated_temperature
  use udar_config, only: tet_stabilised
  implicit none
  private
  public :: element_block_t, pass_outcome_t, block_volume_ratios, material_update, material_finish, &
            block_nodes_done, keep_stiffest, own_step, nodal_reference_volumes, nodal_pressures, nodal_stable_dt, &
            add_block_ticks, element_costs, element_time_steps, block_ratios_done, begin_update_pass, &
            end_update_pass

  integer, parameter :: ld = block_size

  !> One block's work arrays (element index innermost, ld rows).
  type :: element_block_t
    real(rk) :: vol(ld), h(ld)             !< m3 (2D: per revolution or per metre), m
    real(rk) :: d(ld,6), w(ld,3)           !< 1/s: strain rate xx,yy,zz,xy,yz,zx and spin w_xy,w_yz,w_zx
    real(rk) :: j_new(ld), jbar(ld), je(ld), share(ld)   !< -: volume ratios and the element's own share
    real(rk) :: s(ld,6), eps(ld), hard(ld), soft(ld), e_int(ld), p(ld), q(ld)
    real(rk) :: trd(ld), w_dev(ld), w_pl(ld), bulk(ld), visc(ld)
    real(rk) :: eta(ld)                    !< -: rho/rho0 at the step's start
    real(rk) :: g(ld)                      !< Pa: the shear modulus of the stiffness bound
    real(rk) :: lam(ld)                    !< N/m: the stiffness bound the driver puts here, before viscosity
    real(rk) :: dt_el(ld)                  !< s: own step (eroding materials only)
    real(rk) :: p_app(ld), p_node(ld)      !< Pa: the pressure in the element's own forces and in its nodes' average
    logical :: gone(ld), no_shear(ld)
    logical :: erodible = .false., fracturing = .false.
  end type

  !> What an element pass found: the first element (lowest id) with a
  !> non-positive volume and the first whose nodal-averaged volume ratio is
  !> non-positive (0: none), the owned elements eroded by reason, and
  !> whether any local element was eroded.
  type :: pass_outcome_t
    integer :: bad_elem = 0, bad_j = 0, n_eroded(erode_reasons) = 0
    logical :: eroded_any = .false.
    real(rk) :: r_min = huge(1.0_rk)       !< s2, the smallest m/k of the nodes so far
    integer :: dt_node = 0                 !< the node setting it
  end type

contains

  !> Before the first block of a stress update: the owned nodes' sums of
  !> forces, nodal pressures and stiffness bounds start at zero.
  subroutine begin_update_pass(dom)
    type(domain_t), intent(inout) :: dom
    dom%nd_k(1:dom%n_owned_nodes) = 0.0_rk
    dom%nd_f(:,1:dom%n_owned_nodes) = 0.0_rk
    if (dom%anti_locking) dom%nd_p(1:dom%n_owned_nodes) = 0.0_rk
  end subroutine

  !> After the last block: what the pass found, as element_update returns it
  !> (the nodal time step 2 sqrt(min m/k) and its node).
  subroutine end_update_pass(out, bad_elem, bad_j, n_eroded, eroded_any, dt_stable, dt_node)
    type(pass_outcome_t), intent(in) :: out
    integer, intent(out) :: bad_elem, bad_j, n_eroded(erode_reasons)
    logical, intent(out) :: eroded_any
    real(rk), intent(out) :: dt_stable
    integer, intent(out) :: dt_node
    bad_elem = out%bad_elem
    bad_j = out%bad_j
    n_eroded = out%n_eroded
    eroded_any = out%eroded_any
    dt_node = out%dt_node
    dt_stable = huge(1.0_rk)
    if (dt_node > 0) dt_stable = 2.0_rk*sqrt(out%r_min)
  end subroutine

  !> The volume ratio each element's EOS sees: its nodes' averaged ratio
  !> (Bonet-Burton; the mean of nd_j over its corners) or its own.
  subroutine block_volume_ratios(dom, first, nb, eb)
    type(domain_t), intent(in) :: dom
    integer, intent(in) :: first, nb
    type(element_block_t), intent(inout) :: eb
    real(rk) :: acc
    integer :: i, c, e
    if (dom%anti_locking) then
      do i = 1, nb
        e = first + i - 1
        acc = dom%nd_j(dom%el_conn(e,1))
        do c = 2, dom%corners
          acc = acc + dom%nd_j(dom%el_conn(e,c))
        end do
        eb%j_new(i) = dom%corner_share*acc
      end do
    else
      eb%j_new(1:nb) = eb%vol(1:nb)/max(dom%el_vol0(first:first+nb-1), tiny(1.0_rk))
    end if
  end subroutine

  !> The elements' state loaded, inverted ones eroded or reported, eroded
  !> ones at rest, and the stress update: strength (a fractured element
  !> keeps no deviator), then the EOS with the artificial viscosity, which
  !> leave the tangent bulk modulus and the viscosity's stiffening factor.
  subroutine material_update(dom, first, nb, dt, eb, out)
    type(domain_t), intent(inout) :: dom
    integer, intent(in) :: first, nb
    real(rk), intent(in) :: dt
    type(element_block_t), intent(inout) :: eb
    type(pass_outcome_t), intent(inout) :: out
    integer :: i, e, k, last
    logical :: stab
    last = first + nb - 1
    associate (mat => dom%mat(dom%el_mat(first)))
    eb%erodible = erosion_enabled(mat)
    eb%fracturing = fracture_enabled(mat)
    do i = 1, nb
      e = first + i - 1
      eb%gone(i) = dom%el_state(e) == el_eroded
      if (.not. eb%gone(i) .and. (eb%vol(i) <= 0.0_rk .or. eb%j_new(i) <= 0.0_rk)) then
        if (eb%erodible) then
          ! inverted within one step: eroded, never a silent negative volume
          call erode(dom, e, erode_inverted, out)
          eb%gone(i) = .true.
        else if (eb%vol(i) <= 0.0_rk) then
          if (out%bad_elem == 0) out%bad_elem = e    ! stop after this cycle
        else
          if (out%bad_j == 0) out%bad_j = e          ! a neighbour inverted and took the nodal average with it
        end if
      end if
      if (eb%gone(i)) then
        ! at rest at its reference volume, too large to limit the step
        eb%d(i,:) = 0.0_rk
        eb%w(i,:) = 0.0_rk
        eb%h(i) = huge(1.0_rk)
        eb%j_new(i) = dom%el_j(e)
      end if
      ! keep the arithmetic finite until the run stops
      if (eb%vol(i) <= 0.0_rk .or. eb%gone(i)) eb%vol(i) = dom%el_vol0(e)
      if (eb%j_new(i) <= 0.0_rk) eb%j_new(i) = dom%el_j(e)
      eb%no_shear(i) = eb%gone(i) .or. dom%el_state(e) == el_fractured
      ! accumulated total strain: only eroding materials use it
      if (eb%erodible .and. .not. eb%gone(i)) dom%el_eps_tot(e) = dom%el_eps_tot(e) + dt*deviatoric_rate(eb%d(i,:))
    end do
    stab = dom%stab_beta_large > 0.0_rk
    if (stab) then
      ! stabilised: the EOS sees the nodal average blended with the element's own ratio
      eb%jbar(1:nb) = eb%j_new(1:nb)
      eb%je(1:nb) = eb%vol(1:nb)/dom%el_vol0(first:last)
      call blended_volume_ratios(dom%tet_formulation == tet_stabilised, dom%stab_beta, dom%stab_beta_large, &
                                 dom%stab_onset, nb, eb%jbar, eb%je, eb%j_new, eb%share)
      eb%j_new(1:nb) = merge(eb%jbar(1:nb), eb%j_new(1:nb), eb%gone(1:nb))
    end if
    ! fractured and eroded elements keep a zero deviator (set when they
    ! fracture or erode), so it is copied as it is
    do k = 1, 6
      eb%s(1:nb,k) = dom%el_s(first:last,k)
    end do
    eb%eps(1:nb) = dom%el_eps_p(first:last)
    eb%hard(1:nb) = dom%el_hard(first:last)
    eb%soft(1:nb) = dom%el_soft(first:last)
    eb%e_int(1:nb) = dom%el_e(first:last)
    eb%p(1:nb) = dom%el_p(first:last)
    eb%trd(1:nb) = eb%d(1:nb,1) + eb%d(1:nb,2) + eb%d(1:nb,3)
    eb%eta(1:nb) = 1.0_rk/dom%el_j(first:last)
    call strength_block(mat, ld, nb, dt, eb%d, eb%w, eb%soft, dom%el_temp(first:last), eb%p, eb%eta, eb%hard, eb%s, &
                        eb%eps, eb%w_dev, eb%w_pl)
    if (eb%fracturing .or. eb%erodible) then
      ! fractured material carries no shear: no deviatoric work, no flow
      do i = 1, nb
        if (.not. eb%no_shear(i)) cycle
        e = first + i - 1
        eb%s(i,:) = 0.0_rk
        eb%w_dev(i) = 0.0_rk
        eb%w_pl(i) = 0.0_rk
        eb%eps(i) = dom%el_eps_p(e)
        eb%hard(i) = dom%el_hard(e)
      end do
    end if
    call volumetric_update(mat, dom%q_linear, dom%q_quadratic, nb, dt, eb%vol, eb%h, eb%trd, &
                           dom%el_mass(first:last), dom%el_j(first:last), eb%j_new, eb%w_dev, eb%no_shear(1:nb), &
                           eb%e_int, eb%p, eb%q, eb%bulk, eb%visc)
    end associate
  end subroutine

  !> After the driver's stiffness bound (eb%lam): the bound stiffened by
  !> the viscosity, the element's own step (erosion by time step), heating
  !> by plastic work, fracture and erosion, the state kept (el_k 0 when
  !> eroded), and the pressures: p_app in the element's own forces (its
  !> viscosity and all of its pressure (plain), its own share (stabilised)
  !> or none (nodal)), p_node in its nodes' average (0 when eroded or plain).
  subroutine material_finish(dom, first, nb, dt, eb, out)
    type(domain_t), intent(inout) :: dom
    integer, intent(in) :: first, nb
    real(rk), intent(in) :: dt
    type(element_block_t), intent(inout) :: eb
    type(pass_outcome_t), intent(inout) :: out
    real(rk) :: t_old, d_eps
    logical :: fractured, stab, geo, distorted
    integer :: i, e, k, last
    last = first + nb - 1
    stab = dom%stab_beta_large > 0.0_rk
    geo = dom%tet_formulation == tet_stabilised
    associate (mat => dom%mat(dom%el_mat(first)))
    eb%lam(1:nb) = eb%lam(1:nb)*eb%visc(1:nb)
    ! its own step: only erosion by time step asks for it in the cycle
    if (eb%erodible) eb%dt_el(1:nb) = own_step(dom%corner_share, dom%el_mass(first:last), eb%lam(1:nb))
    ! plastic work heats the material (Taylor-Quinney share), which softens it
    do i = 1, nb
      if (eb%w_pl(i) <= 0.0_rk) cycle
      e = first + i - 1
      dom%el_wp(e) = dom%el_wp(e) + eb%w_pl(i)*eb%vol(i)/dom%el_mass(e)
      if (mat%specific_heat > 0.0_rk) then
        t_old = dom%el_temp(e)
        dom%el_temp(e) = t_old + mat%taylor_quinney*eb%w_pl(i)*eb%vol(i)/(dom%el_mass(e)*mat%specific_heat)
        eb%soft(i) = thermal_softening_update(mat, eb%soft(i), t_old, dom%el_temp(e))
      end if
    end do
    ! and, if asked, the viscosity's work and adiabatic compression heat it
    if (mat%shock_heating) then
      do i = 1, nb
        if (eb%gone(i)) cycle
        e = first + i - 1
        t_old = dom%el_temp(e)
        dom%el_temp(e) = shock_heated_temperature(mat%gamma0, mat%specific_heat, t_old, dom%el_j(e), eb%j_new(i), &
                                                  -eb%q(i)*eb%trd(i)*dt*eb%vol(i)/dom%el_mass(e))
        eb%soft(i) = thermal_softening_update(mat, eb%soft(i), t_old, dom%el_temp(e))
      end do
    end if
    if (eb%fracturing .or. eb%erodible) then
      do i = 1, nb
        e = first + i - 1
        if (eb%gone(i)) then
          eb%p(i) = 0.0_rk
          eb%q(i) = 0.0_rk
          cycle
        end if
        if (dom%el_state(e) == el_intact .and. eb%fracturing) then
          d_eps = eb%eps(i) - dom%el_eps_p(e)
          call fracture_update(mat, dt, d_eps, eb%eps(i), von_mises(eb%s(i,:)), eb%p(i), dom%el_temp(e), &
                               dom%el_damage(e), fractured)
          if (fractured) then
            dom%el_state(e) = el_fractured
            eb%s(i,:) = 0.0_rk
            eb%p(i) = max(eb%p(i), 0.0_rk)
          end if
        end if
        if (.not. eb%erodible) cycle
        ! distorted, not fractured: a particle that keeps the strength
        distorted = dom%el_state(e) == el_intact .and. mat%eps_convert > 0.0_rk .and. &
                    dom%el_eps_tot(e) >= mat%eps_convert
        if (dom%el_state(e) == el_fractured .and. dom%el_eps_tot(e) >= mat%eps_erode) then
          call erode(dom, e, erode_strain, out)
        else if (distorted) then
          call erode(dom, e, erode_converted, out)
        else if (eb%dt_el(i) < dom%erode_dt_limit) then
          call erode(dom, e, erode_time_step, out)
        end if
        if (dom%el_state(e) == el_eroded) then
          eb%gone(i) = .true.
          ! the particle of a distorted element takes over its deviator
          ! (particles_convert, this cycle; then zero); any other eroded
          ! element's particle has no strength (theory.md 15)
          if (.not. distorted) eb%s(i,:) = 0.0_rk
          eb%p(i) = 0.0_rk
          eb%q(i) = 0.0_rk
        end if
      end do
    end if
    end associate
    dom%el_k(first:last) = merge(0.0_rk, eb%lam(1:nb), eb%gone(1:nb))
    do k = 1, 6
      dom%el_s(first:last,k) = eb%s(1:nb,k)
    end do
    dom%el_eps_p(first:last) = eb%eps(1:nb)
    dom%el_hard(first:last) = eb%hard(1:nb)
    dom%el_soft(first:last) = eb%soft(1:nb)
    dom%el_e(first:last) = eb%e_int(1:nb)
    dom%el_p(first:last) = eb%p(1:nb)
    dom%el_q(first:last) = eb%q(1:nb)
    dom%el_j(first:last) = eb%j_new(1:nb)
    if (dom%keep_volumes) dom%el_vol(first:last) = eb%vol(1:nb)
    if (dom%keep_altitudes) dom%el_h(first:last) = merge(huge(1.0_rk), eb%h(1:nb), eb%gone(1:nb))
    ! the pressure the element keeps for itself; the nodal pressures' part
    ! follows in the averaged-forces pass
    eb%p_app(1:nb) = eb%q(1:nb)
    if (.not. dom%anti_locking) eb%p_app(1:nb) = eb%p_app(1:nb) + eb%p(1:nb)
    if (stab) eb%p_app(1:nb) = eb%p_app(1:nb) + blended_pressures(geo, .true., eb%share(1:nb), eb%p(1:nb), &
                                                                  eb%j_new(1:nb), 1.0_rk, eb%vol(1:nb)/dom%el_vol0(first:last))
    ! the pressure each element gives its nodes' average
    if (stab) then
      eb%p_node(1:nb) = blended_pressures(geo, .false., eb%share(1:nb), eb%p(1:nb), eb%j_new(1:nb), eb%jbar(1:nb), &
                                          eb%je(1:nb))
      if (dom%keep_volumes) dom%el_pavg(first:last) = eb%p_node(1:nb)
    else
      eb%p_node(1:nb) = eb%p(1:nb)
    end if
    ! an eroded element adds zeros (and the plain element no pressure)
    if (dom%anti_locking) then
      eb%p_node(1:nb) = merge(0.0_rk, eb%p_node(1:nb), eb%gone(1:nb))
    else
      eb%p_node(1:nb) = 0.0_rk
    end if
  end subroutine

  !> Block b completed the element lists of the nodes blk_nd(blk_nd_ptr(b):):
  !> their volume ratios from the sums of their elements' volumes in nd_j
  !> (corner_share of each over Vref; 1 at a node all its elements left).
  subroutine block_ratios_done(dom, b)
    type(domain_t), intent(inout) :: dom
    integer, intent(in) :: b
    integer :: k, n
    do k = dom%blk_nd_ptr(b), dom%blk_nd_ptr(b+1) - 1
      n = dom%blk_nd(k)
      if (dom%nd_vref(n) > 0.0_rk) then
        dom%nd_j(n) = dom%corner_share*dom%nd_j(n)/dom%nd_vref(n)
      else
        dom%nd_j(n) = 1.0_rk
      end if
    end do
  end subroutine

  !> Block b completed the element lists of the nodes blk_nd(blk_nd_ptr(b):):
  !> their averaged pressures (the sums of v0 p over corner_share Vref) and
  !> their part in the nodal time step.
  subroutine block_nodes_done(dom, b, out)
    type(domain_t), intent(inout) :: dom
    integer, intent(in) :: b
    type(pass_outcome_t), intent(inout) :: out
    integer :: k, n
    if (dom%anti_locking) then
      do k = dom%blk_nd_ptr(b), dom%blk_nd_ptr(b+1) - 1
        n = dom%blk_nd(k)
        if (dom%nd_vref(n) <= 0.0_rk) then
          dom%nd_p(n) = 0.0_rk
        else
          dom%nd_p(n) = dom%corner_share*dom%nd_p(n)/dom%nd_vref(n)
        end if
      end do
    end if
    do k = dom%blk_nd_ptr(b), dom%blk_nd_ptr(b+1) - 1
      n = dom%blk_nd(k)
      call keep_stiffest(n, dom%nd_mass(n), dom%nd_k(n), out%r_min, out%dt_node)
    end do
  end subroutine

  !> Sum over the elements at node n that are not eroded, in ascending
  !> element id, of a(e) (times w(e) when given).
  pure real(rk) function alive_incident_sum(dom, n, a, w) result(acc)
    type(domain_t), intent(in) :: dom
    integer, intent(in) :: n
    real(rk), intent(in) :: a(:)
    real(rk), intent(in), optional :: w(:)
    integer :: k, e
    acc = 0.0_rk
    do k = dom%nd_el_ptr(n), dom%nd_el_ptr(n+1) - 1
      e = dom%nd_el(k)
      if (dom%el_state(e) == el_eroded) cycle
      if (present(w)) then
        acc = acc + w(e)*a(e)
      else
        acc = acc + a(e)
      end if
    end do
  end function

  !> Nodal reference volumes V0_a: corner_share (a quarter in 3D) of each incident element's
  !> reference volume, eroded elements left out (again after each erosion).
  !> With rebase (after erosion, anti-locking): each owned node that lost an
  !> element also has the volume its J is taken against rebased so that J
  !> does not jump (a jump would change the pressures without any work);
  !> the other nodes keep theirs to the bit, whatever the partition.
  subroutine nodal_reference_volumes(dom, rebase)
    type(domain_t), intent(inout) :: dom
    logical, intent(in) :: rebase
    real(rk) :: v0
    integer :: n
    do n = 1, dom%n_nodes
      v0 = dom%corner_share*alive_incident_sum(dom, n, dom%el_vol0)
      if (rebase .and. n <= dom%n_owned_nodes .and. v0 /= dom%nd_vol0(n)) then
        dom%nd_vref(n) = 0.0_rk
        if (v0 > 0.0_rk) dom%nd_vref(n) = dom%corner_share*alive_incident_sum(dom, n, dom%el_vol)/dom%nd_j(n)
      end if
      dom%nd_vol0(n) = v0
    end do
  end subroutine

  !> Nodal pressure: the incident elements' EOS pressures weighted by their
  !> reference volumes, over Vref/corner_share (the volume the node's J is taken
  !> against; the weighted mean until erosion rebases Vref): the averaged
  !> forces are then the exact gradient of the averaged-volume energy, also
  !> after erosion (theory.md section 8). Eroded elements left out. element_update
  !> computes them as it goes (the same sums in the same order); again here
  !> after erosion changed nd_vol0.
  subroutine nodal_pressures(dom)
    type(domain_t), intent(inout) :: dom
    integer :: n
    do n = 1, dom%n_owned_nodes
      call node_pressure(dom, n)
    end do
  end subroutine

  subroutine node_pressure(dom, n)
    type(domain_t), intent(inout) :: dom
    integer, intent(in) :: n
    dom%nd_p(n) = 0.0_rk
    if (dom%nd_vref(n) <= 0.0_rk) return
    if (dom%stab_beta_large > 0.0_rk) then
      dom%nd_p(n) = dom%corner_share*alive_incident_sum(dom, n, dom%el_pavg, w=dom%el_vol0)/dom%nd_vref(n)
    else
      dom%nd_p(n) = dom%corner_share*alive_incident_sum(dom, n, dom%el_p, w=dom%el_vol0)/dom%nd_vref(n)
    end if
  end subroutine

  !> The nodal time step (theory.md section 9): K <= diag(sum of the
  !> incident elements' stiffness bounds), so the highest frequency of the
  !> lumped-mass mesh is at most max_n sqrt(k_n/m_n) and
  !>   dt = min_n 2 sqrt(m_n/k_n),  k_n = sum_(e at n) el_k(e)
  !> is stable. Over the owned nodes; node = the one setting it (0: none).
  subroutine nodal_stable_dt(dom, dt_stable, node)
    type(domain_t), intent(in) :: dom
    real(rk), intent(out) :: dt_stable
    integer, intent(out) :: node
    real(rk) :: k_n, r_min
    integer :: n, k
    dt_stable = huge(1.0_rk)
    node = 0
    r_min = huge(1.0_rk)
    do n = 1, dom%n_owned_nodes
      k_n = 0.0_rk
      do k = dom%nd_el_ptr(n), dom%nd_el_ptr(n+1) - 1
        k_n = k_n + dom%el_k(dom%nd_el(k))
      end do
      call keep_stiffest(n, dom%nd_mass(n), k_n, r_min, node)
    end do
    if (node > 0) dt_stable = 2.0_rk*sqrt(r_min)
  end subroutine

  !> Block b's measured time (blk_ticks) grows by the clock ticks since tick0.
  subroutine add_block_ticks(dom, b, tick0)
    type(domain_t), intent(inout) :: dom
    integer, intent(in) :: b
    integer(i8), intent(in) :: tick0
    integer(i8) :: tick1
    call system_clock(tick1)
    dom%blk_ticks(b) = dom%blk_ticks(b) + (tick1 - tick0)
  end subroutine

  !> The measured cost of every local element for a partition (&run
  !> rebalance_imbalance): its block's time in the element passes since the
  !> run or the last repartition over the block's elements, in clock ticks (an
  !> element flowing plastically costs up to about twice an elastic one,
  !> its radial return: performance.md, "Where the 2-rank speedup goes").
  subroutine element_costs(dom, cost)
    type(domain_t), intent(in) :: dom
    real(rk), intent(out) :: cost(:)
    integer :: b
    do b = 1, dom%n_blocks
      cost(dom%blk_first(b):dom%blk_last(b)) = real(dom%blk_ticks(b), rk)/(dom%blk_last(b) - dom%blk_first(b) + 1)
    end do
  end subroutine

  !> Every element's own stable step (own_step of its last stiffness
  !> bound; huge for eroded elements), for output.
  subroutine element_time_steps(dom, dt_el)
    type(domain_t), intent(in) :: dom
    real(rk), intent(out) :: dt_el(:)
    dt_el = own_step(dom%corner_share, dom%el_mass, dom%el_k)
  end subroutine

  !> Element e leaves the mesh: its mass stays at its nodes, its internal
  !> energy (frozen from now on) is the eroded energy.
  subroutine erode(dom, e, reason, out)
    type(domain_t), intent(inout) :: dom
    integer, intent(in) :: e, reason
    type(pass_outcome_t), intent(inout) :: out
    dom%el_state(e) = el_eroded
    out%eroded_any = .true.
    if (dom%el_owned(e)) out%n_eroded(reason) = out%n_eroded(reason) + 1
  end subroutine

  !> The smallest m/k so far and its node (the lowest index among equal
  !> ratios, so the answer does not depend on the order nodes come in);
  !> nodes without stiffness do not limit the step.
  pure subroutine keep_stiffest(n, mass, k_n, r_min, node)
    integer, intent(in) :: n
    real(rk), intent(in) :: mass, k_n
    real(rk), intent(inout) :: r_min
    integer, intent(inout) :: node
    real(rk) :: r
    if (k_n <= 0.0_rk) return
    r = mass/k_n
    if (r < r_min .or. (r == r_min .and. n < node)) then
      r_min = r
      node = n
    end if
  end subroutine

  !> An element's own stable step from its stiffness bound and its lumped
  !> mass (corner_share of it at each node): the nodal step of the element alone.
  elemental real(rk) function own_step(corner_share, mass, k) result(dt)
    real(rk), intent(in) :: corner_share, mass, k
    dt = huge(1.0_rk)
    if (k > 0.0_rk) dt = 2.0_rk*sqrt(corner_share*mass/k)
  end function
end module udar_element_shared
