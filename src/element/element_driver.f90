!> Element passes of one cycle, over vectorized blocks: gather nodal data,
!> call the pure kernels, keep element state. Nodal averages (anti-locking)
!> run over the node->element lists in ascending element id, inside the
!> element passes as each node's list completes; the nodal forces are
!> added element by element in ascending id (the same order). So every
!> sum has one fixed order whatever the partition. Element passes cover
!> every local element (owned and ghost); nodal sums the owned nodes,
!> whose element lists are complete.
module udar_element_driver
  use udar_kinds, only: rk, i8
  use udar_domain, only: domain_t, block_size
  use udar_tet4, only: tet_gradients, tet_velocity_gradient, tet_internal_forces, tet_pressure_forces, tet_volumes, &
      tet_stiffness_bound
  use udar_strength, only: strength_block, thermal_softening_update, von_mises
  use udar_fracture, only: el_fractured, el_eroded, el_intact, erode_strain, erode_time_step, erode_inverted, &
      fracture_update, fracture_enabled, erosion_enabled, deviatoric_rate
  use udar_hydro, only: volumetric_update, dilatational_speed2, blended_volume_ratios, blended_pressures, &
      step_shear_modulus, step_volumetric_share, tangent_bulk_modulus
  use udar_config, only: tet_stabilised
  implicit none
  private
  public :: element_volumes, element_update, nodal_pressures, element_forces_averaged, element_stiffness_bounds, &
            nodal_stable_dt, element_time_steps, nodal_reference_volumes, element_altitudes, current_volume, &
            element_costs

contains

  !> The owned nodes' volume ratios from the current coordinates:
  !> J_a = V_a / Vref_a, V_a a quarter of each incident
  !> element's volume (Bonet and Burton 1998), Vref_a = V0_a until erosion
  !> rebases it; eroded elements left out, 1 at a node they all left. The
  !> volumes are added to nd_j element by element in ascending id (each
  !> node's list order), and a node's ratio is formed once the block holding
  !> its last element is done (domain_t blk_nd).
  subroutine element_volumes(dom)
    type(domain_t), intent(inout) :: dom
    real(rk) :: xe(block_size,4,3), vol(block_size)
    integer :: b, k, n, i, c, first, nb
    integer(i8) :: tick0
    dom%nd_j(1:dom%n_owned_nodes) = 0.0_rk
    do b = 1, dom%n_blocks
      if (dom%time_blocks) call system_clock(tick0)
      first = dom%blk_first(b)
      nb = dom%blk_last(b) - first + 1
      call gather_block(dom, dom%nd_x, first, nb, xe)
      ! into the block only: element_update stores the same volumes
      call tet_volumes(block_size, nb, xe, vol)
      do i = 1, nb
        if (dom%el_state(first+i-1) == el_eroded) cycle
        do c = 1, 4
          n = dom%el_conn(first+i-1,c)
          if (n <= dom%n_owned_nodes) dom%nd_j(n) = dom%nd_j(n) + vol(i)
        end do
      end do
      do k = dom%blk_nd_ptr(b), dom%blk_nd_ptr(b+1) - 1
        n = dom%blk_nd(k)
        if (dom%nd_vref(n) > 0.0_rk) then
          dom%nd_j(n) = 0.25_rk*dom%nd_j(n)/dom%nd_vref(n)
        else
          dom%nd_j(n) = 1.0_rk
        end if
      end do
      if (dom%time_blocks) call add_block_ticks(dom, b, tick0)
    end do
  end subroutine

  !> Volume of element e at the current coordinates (el_vol is kept only
  !> where erosion needs it).
  real(rk) function current_volume(dom, e) result(v)
    type(domain_t), intent(in) :: dom
    integer, intent(in) :: e
    real(rk) :: xe(block_size,4,3), vol(1)
    call gather_block(dom, dom%nd_x, e, 1, xe)
    call tet_volumes(block_size, 1, xe, vol)
    v = vol(1)
  end function

  !> Smallest altitude of every element from the nodal coordinates (huge
  !> for eroded elements), as element_update keeps it.
  subroutine element_altitudes(dom)
    type(domain_t), intent(inout) :: dom
    real(rk) :: grad(block_size,4,3), vol(block_size), g2max(block_size)
    integer :: b, nb, first, last
    do b = 1, dom%n_blocks
      call block_geometry(dom, b, first, last, nb, vol, grad, g2max)
      dom%el_h(first:last) = merge(huge(1.0_rk), 1.0_rk/sqrt(g2max(1:nb)), dom%el_state(first:last) == el_eroded)
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

  !> Nodal reference volumes V0_a: a quarter of each incident element's
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
      v0 = 0.25_rk*alive_incident_sum(dom, n, dom%el_vol0)
      if (rebase .and. n <= dom%n_owned_nodes .and. v0 /= dom%nd_vol0(n)) then
        dom%nd_vref(n) = 0.0_rk
        if (v0 > 0.0_rk) dom%nd_vref(n) = 0.25_rk*alive_incident_sum(dom, n, dom%el_vol)/dom%nd_j(n)
      end if
      dom%nd_vol0(n) = v0
    end do
  end subroutine

  !> Nodal pressure: the incident elements' EOS pressures weighted by their
  !> reference volumes, over 4 Vref (the volume the node's J is taken
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
      dom%nd_p(n) = 0.25_rk*alive_incident_sum(dom, n, dom%el_pavg, w=dom%el_vol0)/dom%nd_vref(n)
    else
      dom%nd_p(n) = 0.25_rk*alive_incident_sum(dom, n, dom%el_p, w=dom%el_vol0)/dom%nd_vref(n)
    end if
  end subroutine

  !> Stress update of every element over dt with the velocities v(n+1/2) on
  !> the geometry x(n+1); the nodal forces too unless anti-locking needs the
  !> nodal pressures first, which are then computed (nodal_pressures) as the
  !> blocks complete each owned node's element list. Fracture and erosion: a fractured element keeps no
  !> deviator and no tension; an eroded one passes through the kernels as an
  !> element at rest (no strain, no force, its state frozen) and is left out
  !> of the time step. Keeps each element's stiffness bound for the nodal
  !> time step (el_k, 0 when eroded). Returns the first
  !> element (lowest id) with a non-positive volume and the first whose
  !> nodal-averaged volume ratio is non-positive (a neighbour inverted), or
  !> 0 (elements of eroding materials are eroded instead), the owned
  !> elements eroded this cycle by reason (udar_fracture erode_*), and
  !> whether any local element was eroded. Also the nodal time step of the
  !> new bounds over the owned nodes and its node (nodal_stable_dt's result,
  !> bitwise: the same sums in the same order, formed as the blocks complete
  !> each node's element list instead of in a pass of their own).
  subroutine element_update(dom, dt, bad_elem, bad_j, n_eroded, eroded_any, dt_stable, dt_node)
    type(domain_t), intent(inout) :: dom
    real(rk), intent(in) :: dt
    integer, intent(out) :: bad_elem, bad_j, n_eroded(3)
    logical, intent(out) :: eroded_any
    real(rk), intent(out) :: dt_stable
    integer, intent(out) :: dt_node
    integer, parameter :: ld = block_size
    real(rk) :: ve(ld,4,3), grad(ld,4,3), fe(ld,4,3)
    real(rk) :: vol(ld), h(ld), d(ld,6), w(ld,3), s(ld,6), p_app(ld), trd(ld), j_new(ld), &
                w_dev(ld), w_pl(ld), eps(ld), hard(ld), soft(ld), e_int(ld), p(ld), q(ld), dt_el(ld), &
                bulk(ld), visc(ld), lam(ld), p_node(ld)
    logical :: gone(ld), no_shear(ld), erodible, fracturing, fractured, stab, geo
    real(rk) :: t_old, d_eps, jbar(ld), je(ld), share(ld), r_min
    integer :: b, i, e, nb, first, last, k, n
    integer(i8) :: tick0
    r_min = huge(1.0_rk)
    dt_node = 0
    dom%nd_k(1:dom%n_owned_nodes) = 0.0_rk
    bad_elem = 0
    bad_j = 0
    n_eroded = 0
    eroded_any = .false.
    stab = dom%stab_beta_large > 0.0_rk
    geo = dom%tet_formulation == tet_stabilised
    dom%nd_f(:,1:dom%n_owned_nodes) = 0.0_rk
    if (dom%anti_locking) dom%nd_p(1:dom%n_owned_nodes) = 0.0_rk
    do b = 1, dom%n_blocks
      if (dom%time_blocks) call system_clock(tick0)
      call block_geometry(dom, b, first, last, nb, vol, grad, h)
      call gather_block(dom, dom%nd_v, first, nb, ve)
      h(1:nb) = 1.0_rk/sqrt(h(1:nb))      ! smallest altitude
      call tet_velocity_gradient(ld, nb, ve, grad, d, w)
      associate (mat => dom%mat(dom%el_mat(first)))
      erodible = erosion_enabled(mat)
      fracturing = fracture_enabled(mat)
      ! volume ratio seen by the EOS: nodal average (Bonet-Burton) or the element's own
      if (dom%anti_locking) then
        do i = 1, nb
          e = first + i - 1
          j_new(i) = 0.25_rk*(dom%nd_j(dom%el_conn(e,1)) + dom%nd_j(dom%el_conn(e,2)) &
                            + dom%nd_j(dom%el_conn(e,3)) + dom%nd_j(dom%el_conn(e,4)))
        end do
      else
        j_new(1:nb) = vol(1:nb)/max(dom%el_vol0(first:last), tiny(1.0_rk))
      end if
      do i = 1, nb
        e = first + i - 1
        gone(i) = dom%el_state(e) == el_eroded
        if (.not. gone(i) .and. (vol(i) <= 0.0_rk .or. j_new(i) <= 0.0_rk)) then
          if (erodible) then
            ! inverted within one step: eroded, never a silent negative volume
            call erode(e, erode_inverted)
            gone(i) = .true.
          else if (vol(i) <= 0.0_rk) then
            if (bad_elem == 0) bad_elem = e    ! stop after this cycle
          else
            if (bad_j == 0) bad_j = e          ! a neighbour inverted and took the nodal average with it
          end if
        end if
        if (gone(i)) then
          ! at rest at its reference volume, too large to limit the step
          d(i,:) = 0.0_rk
          w(i,:) = 0.0_rk
          h(i) = huge(1.0_rk)
          j_new(i) = dom%el_j(e)
        end if
        ! keep the arithmetic finite until the run stops
        if (vol(i) <= 0.0_rk .or. gone(i)) vol(i) = dom%el_vol0(e)
        if (j_new(i) <= 0.0_rk) j_new(i) = dom%el_j(e)
        no_shear(i) = gone(i) .or. dom%el_state(e) == el_fractured
        ! accumulated total strain: only eroding materials use it
        if (erodible .and. .not. gone(i)) dom%el_eps_tot(e) = dom%el_eps_tot(e) + dt*deviatoric_rate(d(i,:))
      end do
      if (stab) then
        ! stabilised: the EOS sees the nodal average blended with the element's own ratio
        jbar(1:nb) = j_new(1:nb)
        je(1:nb) = vol(1:nb)/dom%el_vol0(first:last)
        call blended_volume_ratios(geo, dom%stab_beta, dom%stab_beta_large, dom%stab_onset, nb, jbar, je, j_new, share)
        j_new(1:nb) = merge(jbar(1:nb), j_new(1:nb), gone(1:nb))
      end if
      ! fractured and eroded elements keep a zero deviator (set when they
      ! fracture or erode), so it is copied as it is
      do k = 1, 6
        s(1:nb,k) = dom%el_s(first:last,k)
      end do
      eps(1:nb) = dom%el_eps_p(first:last)
      hard(1:nb) = dom%el_hard(first:last)
      soft(1:nb) = dom%el_soft(first:last)
      e_int(1:nb) = dom%el_e(first:last)
      p(1:nb) = dom%el_p(first:last)
      trd(1:nb) = d(1:nb,1) + d(1:nb,2) + d(1:nb,3)
        call strength_block(mat, ld, nb, dt, d, w, soft, hard, s, eps, w_dev, w_pl)
        if (fracturing .or. erodible) then
          ! fractured material carries no shear: no deviatoric work, no flow
          do i = 1, nb
            if (.not. no_shear(i)) cycle
            e = first + i - 1
            s(i,:) = 0.0_rk
            w_dev(i) = 0.0_rk
            w_pl(i) = 0.0_rk
            eps(i) = dom%el_eps_p(e)
            hard(i) = dom%el_hard(e)
          end do
        end if
        call volumetric_update(mat, dom%q_linear, dom%q_quadratic, nb, dt, vol, h, trd, &
                               dom%el_mass(first:last), dom%el_j(first:last), j_new, w_dev, no_shear(1:nb), &
                               e_int, p, q, bulk, visc)
        ! the element's stiffness bound (stiffened by its viscosity) and its own step
        call tet_stiffness_bound(ld, nb, vol, grad, bulk, step_shear_modulus(mat), &
                                 step_volumetric_share(dom%anti_locking, dom%stab_beta_large), lam)
        lam(1:nb) = lam(1:nb)*visc(1:nb)
        ! its own step: only erosion by time step asks for it in the cycle
        if (erodible) dt_el(1:nb) = own_step(dom%el_mass(first:last), lam(1:nb))
        ! plastic work heats the material (Taylor-Quinney share), which softens it
        do i = 1, nb
          if (w_pl(i) <= 0.0_rk) cycle
          e = first + i - 1
          dom%el_wp(e) = dom%el_wp(e) + w_pl(i)*vol(i)/dom%el_mass(e)
          if (mat%specific_heat > 0.0_rk) then
            t_old = dom%el_temp(e)
            dom%el_temp(e) = t_old + mat%taylor_quinney*w_pl(i)*vol(i)/(dom%el_mass(e)*mat%specific_heat)
            soft(i) = thermal_softening_update(mat, soft(i), t_old, dom%el_temp(e))
          end if
        end do
        if (fracturing .or. erodible) then
          do i = 1, nb
            e = first + i - 1
            if (gone(i)) then
              p(i) = 0.0_rk
              q(i) = 0.0_rk
              cycle
            end if
            if (dom%el_state(e) == el_intact .and. fracturing) then
              d_eps = eps(i) - dom%el_eps_p(e)
              call fracture_update(mat, dt, d_eps, eps(i), von_mises(s(i,:)), p(i), dom%el_temp(e), &
                                   dom%el_damage(e), fractured)
              if (fractured) then
                dom%el_state(e) = el_fractured
                s(i,:) = 0.0_rk
                p(i) = max(p(i), 0.0_rk)
              end if
            end if
            if (.not. erodible) cycle
            if (dom%el_state(e) == el_fractured .and. dom%el_eps_tot(e) >= mat%eps_erode) then
              call erode(e, erode_strain)
            else if (dt_el(i) < dom%erode_dt_limit) then
              call erode(e, erode_time_step)
            end if
            if (dom%el_state(e) == el_eroded) then
              gone(i) = .true.
              s(i,:) = 0.0_rk
              p(i) = 0.0_rk
              q(i) = 0.0_rk
            end if
          end do
        end if
      end associate
      dom%el_k(first:last) = merge(0.0_rk, lam(1:nb), gone(1:nb))
      do k = 1, 6
        dom%el_s(first:last,k) = s(1:nb,k)
      end do
      dom%el_eps_p(first:last) = eps(1:nb)
      dom%el_hard(first:last) = hard(1:nb)
      dom%el_soft(first:last) = soft(1:nb)
      dom%el_e(first:last) = e_int(1:nb)
      dom%el_p(first:last) = p(1:nb)
      dom%el_q(first:last) = q(1:nb)
      dom%el_j(first:last) = j_new(1:nb)
      if (dom%keep_volumes) dom%el_vol(first:last) = vol(1:nb)
      if (dom%keep_altitudes) dom%el_h(first:last) = merge(huge(1.0_rk), h(1:nb), gone(1:nb))
      ! forces of the deviator, the viscosity and the pressure the element
      ! keeps for itself: all of it (plain), its own share (stabilised) or
      ! none (nodal); the nodal pressures' part follows in
      ! element_forces_averaged
      p_app(1:nb) = q(1:nb)
      if (.not. dom%anti_locking) p_app(1:nb) = p_app(1:nb) + p(1:nb)
      if (stab) p_app(1:nb) = p_app(1:nb) + blended_pressures(geo, .true., share(1:nb), p(1:nb), j_new(1:nb), &
                                                              1.0_rk, vol(1:nb)/dom%el_vol0(first:last))
      call tet_internal_forces(ld, nb, vol, grad, s, p_app, fe)
      do i = 1, nb
        if (gone(i)) fe(i,:,:) = 0.0_rk
      end do
      ! the pressure each element gives its nodes' average (nodal_pressures)
      if (stab) then
        p_node(1:nb) = blended_pressures(geo, .false., share(1:nb), p(1:nb), j_new(1:nb), jbar(1:nb), je(1:nb))
        if (dom%keep_volumes) dom%el_pavg(first:last) = p_node(1:nb)
      else
        p_node(1:nb) = p(1:nb)
      end if
      ! forces, nodal pressures and stiffness sums added element by element
      ! in ascending id, each node's mean formed once its last element is
      ! done; an eroded element adds zeros (and the plain element no pressure)
      if (dom%anti_locking) then
        p_node(1:nb) = merge(0.0_rk, p_node(1:nb), gone(1:nb))
      else
        p_node(1:nb) = 0.0_rk
      end if
      call add_forces(dom, first, nb, fe, dom%el_vol0(first:last), p_node, dom%el_k(first:last))
      if (dom%anti_locking) then
        do k = dom%blk_nd_ptr(b), dom%blk_nd_ptr(b+1) - 1
          n = dom%blk_nd(k)
          if (dom%nd_vref(n) <= 0.0_rk) then
            dom%nd_p(n) = 0.0_rk
          else
            dom%nd_p(n) = 0.25_rk*dom%nd_p(n)/dom%nd_vref(n)
          end if
        end do
      end if
      do k = dom%blk_nd_ptr(b), dom%blk_nd_ptr(b+1) - 1
        n = dom%blk_nd(k)
        call keep_stiffest(n, dom%nd_mass(n), dom%nd_k(n), r_min, dt_node)
      end do
      if (dom%time_blocks) call add_block_ticks(dom, b, tick0)
    end do
    dt_stable = huge(1.0_rk)
    if (dt_node > 0) dt_stable = 2.0_rk*sqrt(r_min)
  contains
    !> Element e leaves the mesh: its mass stays at its nodes, its internal
    !> energy (frozen from now on) is the eroded energy.
    subroutine erode(e, reason)
      integer, intent(in) :: e, reason
      dom%el_state(e) = el_eroded
      eroded_any = .true.
      if (dom%el_owned(e)) n_eroded(reason) = n_eroded(reason) + 1
    end subroutine
  end subroutine

  !> The stiffness bounds el_k of the current state without advancing it
  !> (start-up and restart: no viscosity).
  subroutine element_stiffness_bounds(dom)
    type(domain_t), intent(inout) :: dom
    integer, parameter :: ld = block_size
    real(rk) :: grad(ld,4,3), vol(ld), h(ld), c2(ld), bulk(ld), lam(ld), g
    integer :: b, nb, first, last
    do b = 1, dom%n_blocks
      call block_geometry(dom, b, first, last, nb, vol, grad, h)
      associate (mat => dom%mat(dom%el_mat(first)))
        g = step_shear_modulus(mat)
        call dilatational_speed2(mat, nb, dom%el_j(first:last), dom%el_p(first:last), dom%el_mass(first:last), vol, c2)
        bulk(1:nb) = tangent_bulk_modulus(c2(1:nb), dom%el_mass(first:last)/vol(1:nb), 4.0_rk/3.0_rk*g)
        call tet_stiffness_bound(ld, nb, vol, grad, bulk, g, step_volumetric_share(dom%anti_locking, dom%stab_beta_large), &
                                 lam)
      end associate
      dom%el_k(first:last) = merge(0.0_rk, lam(1:nb), dom%el_state(first:last) == el_eroded)
    end do
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
  !> mass (a quarter at each node): the nodal step of the element alone.
  elemental real(rk) function own_step(mass, k) result(dt)
    real(rk), intent(in) :: mass, k
    dt = huge(1.0_rk)
    if (k > 0.0_rk) dt = 2.0_rk*sqrt(0.25_rk*mass/k)
  end function

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
    dt_el = own_step(dom%el_mass, dom%el_k)
  end subroutine

  !> The nodal pressures' forces: each element's share of them, the mean
  !> of its nodes' averaged pressures, added to the owned nodes' forces
  !> (add_forces) after the rest of its forces (element_update). Needs only
  !> the coordinates, not the gradients: V grad N_a is a cofactor vector
  !> (tet_pressure_forces).
  subroutine element_forces_averaged(dom)
    type(domain_t), intent(inout) :: dom
    integer, parameter :: ld = block_size
    real(rk) :: p_bar(ld), fe(ld,4,3), xe(ld,4,3)
    integer :: b, i, e, nb, first
    integer(i8) :: tick0
    do b = 1, dom%n_blocks
      if (dom%time_blocks) call system_clock(tick0)
      first = dom%blk_first(b)
      nb = dom%blk_last(b) - first + 1
      call gather_block(dom, dom%nd_x, first, nb, xe)
      do i = 1, nb
        e = first + i - 1
        ! a fractured element's mean is not clipped: clipping it broke the
        ! work identity of theory.md section 8 (energy from nowhere, validation.md 4g)
        p_bar(i) = 0.25_rk*(dom%nd_p(dom%el_conn(e,1)) + dom%nd_p(dom%el_conn(e,2)) &
                 + dom%nd_p(dom%el_conn(e,3)) + dom%nd_p(dom%el_conn(e,4)))
        if (dom%el_state(e) == el_eroded) p_bar(i) = 0.0_rk
      end do
      call tet_pressure_forces(ld, nb, xe, p_bar, fe)
      call add_forces(dom, first, nb, fe)
      if (dom%time_blocks) call add_block_ticks(dom, b, tick0)
    end do
  end subroutine

  !> Element range of block b and its geometry at the current coordinates:
  !> volumes, shape-function gradients and g2max (see tet_gradients).
  subroutine block_geometry(dom, b, first, last, nb, vol, grad, g2max)
    type(domain_t), intent(in) :: dom
    integer, intent(in) :: b
    integer, intent(out) :: first, last, nb
    real(rk), intent(inout) :: vol(block_size), grad(block_size,4,3), g2max(block_size)
    real(rk) :: xe(block_size,4,3)
    first = dom%blk_first(b)
    last = dom%blk_last(b)
    nb = last - first + 1
    call gather_block(dom, dom%nd_x, first, nb, xe)
    call tet_gradients(block_size, nb, xe, vol, grad, g2max)
  end subroutine

  !> Nodal vectors a(3,n) of the nb elements from first on, into a block (ld,4,3).
  !> Element by element, each node's three components as one short copy: on
  !> AVX-512 hardware gathers (what gcc makes of the vectorized form) cost
  !> more than the plain loads.
  subroutine gather_block(dom, a, first, nb, block)
    type(domain_t), intent(in) :: dom
    real(rk), intent(in) :: a(3,*)
    integer, intent(in) :: first, nb
    real(rk), intent(inout) :: block(block_size,4,3)
    integer :: i, c, node
    !GCC$ novector
    do i = 1, nb
      do c = 1, 4
        node = dom%el_conn(first+i-1, c)
        block(i,c,1) = a(1,node); block(i,c,2) = a(2,node); block(i,c,3) = a(3,node)
      end do
    end do
  end subroutine

  !> Block forces (ld,4,3) added to the owned nodes' forces, element after
  !> element, and when given, in the same sweep, each owned node's sums of
  !> the volume-weighted pressures (v0 p) and of the stiffness bounds k_el:
  !> each node's sums run in ascending element id, the order of its
  !> node->element list. nd_f, nd_p and nd_k of the owned nodes are zeroed
  !> before the first block. (The test of the optional sums is loop
  !> invariant: gcc unswitches the loop.)
  subroutine add_forces(dom, first, nb, fe, v0, p, k_el)
    type(domain_t), intent(inout) :: dom
    integer, intent(in) :: first, nb
    real(rk), intent(in) :: fe(block_size,4,3)
    real(rk), intent(in), optional :: v0(nb), p(block_size), k_el(nb)
    integer :: a, i, n
    do i = 1, nb
      do a = 1, 4
        n = dom%el_conn(first+i-1, a)
        if (n > dom%n_owned_nodes) cycle
        dom%nd_f(1,n) = dom%nd_f(1,n) + fe(i,a,1)
        dom%nd_f(2,n) = dom%nd_f(2,n) + fe(i,a,2)
        dom%nd_f(3,n) = dom%nd_f(3,n) + fe(i,a,3)
        if (present(k_el)) then
          dom%nd_p(n) = dom%nd_p(n) + v0(i)*p(i)
          dom%nd_k(n) = dom%nd_k(n) + k_el(i)
        end if
      end do
    end do
  end subroutine
end module udar_element_driver
