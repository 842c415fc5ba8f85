!> The 3D (tet4) element passes of one cycle, over vectorized blocks: gather nodal data,
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
  use udar_fracture, only: el_eroded, erode_reasons
  use udar_config, only: shear_constant
  use udar_hydro, only: dilatational_speed2, step_shear_modulus, element_shear_moduli, step_volumetric_share, &
      tangent_bulk_modulus
  use udar_element_shared, only: element_block_t, pass_outcome_t, block_volume_ratios, material_update, &
      material_finish, block_nodes_done, add_block_ticks, block_ratios_done, begin_update_pass, end_update_pass
  implicit none
  private
  public :: element_volumes, element_update, element_forces_averaged, element_stiffness_bounds, &
            element_altitudes, current_volume

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
    integer :: b, n, i, c, first, nb
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
      call block_ratios_done(dom, b)
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
    integer, intent(out) :: bad_elem, bad_j, n_eroded(erode_reasons)
    logical, intent(out) :: eroded_any
    real(rk), intent(out) :: dt_stable
    integer, intent(out) :: dt_node
    integer, parameter :: ld = block_size
    real(rk) :: ve(ld,4,3), grad(ld,4,3), fe(ld,4,3)
    type(element_block_t) :: eb
    type(pass_outcome_t) :: out
    integer :: b, i, nb, first, last
    integer(i8) :: tick0
    call begin_update_pass(dom)
    do b = 1, dom%n_blocks
      if (dom%time_blocks) call system_clock(tick0)
      call block_geometry(dom, b, first, last, nb, eb%vol, grad, eb%h)
      call gather_block(dom, dom%nd_v, first, nb, ve)
      eb%h(1:nb) = 1.0_rk/sqrt(eb%h(1:nb))      ! smallest altitude
      call tet_velocity_gradient(ld, nb, ve, grad, eb%d, eb%w)
      call block_volume_ratios(dom, first, nb, eb)
      call material_update(dom, first, nb, dt, eb, out)
      ! the element's stiffness bound (material_finish stiffens it by its viscosity)
      if (dom%mat(dom%el_mat(first))%shear_model == shear_constant) then
        call tet_stiffness_bound(ld, nb, eb%vol, grad, eb%bulk, step_shear_modulus(dom%mat(dom%el_mat(first))), &
                                 step_volumetric_share(dom%anti_locking, dom%stab_beta_large), eb%lam)
      else
        call element_shear_moduli(dom%mat(dom%el_mat(first)), nb, eb%p, dom%el_temp(first:last), eb%j_new, eb%g)
        call tet_stiffness_bound(ld, nb, eb%vol, grad, eb%bulk, 0.0_rk, &
                                 step_volumetric_share(dom%anti_locking, dom%stab_beta_large), eb%lam, eb%g)
      end if
      call material_finish(dom, first, nb, dt, eb, out)
      ! forces of the deviator, the viscosity and the pressure the element
      ! keeps for itself; the nodal pressures' part follows in
      ! element_forces_averaged
      call tet_internal_forces(ld, nb, eb%vol, grad, eb%s, eb%p_app, fe)
      do i = 1, nb
        if (eb%gone(i)) fe(i,:,:) = 0.0_rk
      end do
      ! forces, nodal pressures and stiffness sums added element by element
      ! in ascending id, each node's mean formed once its last element is done
      call add_forces(dom, first, nb, fe, dom%el_vol0(first:last), eb%p_node, dom%el_k(first:last))
      call block_nodes_done(dom, b, out)
      if (dom%time_blocks) call add_block_ticks(dom, b, tick0)
    end do
    call end_update_pass(out, bad_elem, bad_j, n_eroded, eroded_any, dt_stable, dt_node)
  end subroutine

  !> The stiffness bounds el_k of the current state without advancing it
  !> (start-up and restart: no viscosity).
  subroutine element_stiffness_bounds(dom)
    type(domain_t), intent(inout) :: dom
    integer, parameter :: ld = block_size
    real(rk) :: grad(ld,4,3), vol(ld), h(ld), c2(ld), bulk(ld), lam(ld), g, g_el(ld)
    integer :: b, nb, first, last
    do b = 1, dom%n_blocks
      call block_geometry(dom, b, first, last, nb, vol, grad, h)
      associate (mat => dom%mat(dom%el_mat(first)))
        g = step_shear_modulus(mat)
        call dilatational_speed2(mat, nb, dom%el_j(first:last), dom%el_p(first:last), dom%el_mass(first:last), vol, c2)
        bulk(1:nb) = tangent_bulk_modulus(c2(1:nb), dom%el_mass(first:last)/vol(1:nb), 4.0_rk/3.0_rk*g)
        if (mat%shear_model == shear_constant) then
          call tet_stiffness_bound(ld, nb, vol, grad, bulk, g, step_volumetric_share(dom%anti_locking, dom%stab_beta_large), &
                                   lam)
        else
          call element_shear_moduli(mat, nb, dom%el_p(first:last), dom%el_temp(first:last), dom%el_j(first:last), g_el)
          call tet_stiffness_bound(ld, nb, vol, grad, bulk, 0.0_rk, &
                                   step_volumetric_share(dom%anti_locking, dom%stab_beta_large), lam, g_el)
        end if
      end associate
      dom%el_k(first:last) = merge(0.0_rk, lam(1:nb), dom%el_state(first:last) == el_eroded)
    end do
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
