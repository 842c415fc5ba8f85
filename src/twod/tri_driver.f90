!> Element passes of one cycle in 2D (axisymmetric or plane strain), over
!> the vectorized blocks of three-node triangles: the counterpart of the 3D
!> udar_element_driver with the tri3 kernels; the material half of the
!> update (strength, EOS, viscosity, fracture, erosion) and the nodal
!> averages are udar_element_shared's, the same as in 3D. Coordinates and
!> velocities are the nodal vectors' first two components (r, z or x, y;
!> the third stays 0). The element volumes are per full revolution
!> (2 pi rbar A) or per metre of thickness (A), and so are the masses,
!> forces and energies made from them (theory.md section 14).
module udar_tri_driver
  use udar_kinds, only: rk, i8, pi
  use udar_domain, only: domain_t, block_size
  use udar_config, only: geometry_axisymmetric
  use udar_tri3, only: tri_geometry, tri_smallest_altitude, tri_velocity_gradient, tri_internal_forces, &
      tri_stiffness_bound, tri_patch_share
  use udar_fracture, only: el_eroded, erode_reasons
  use udar_config, only: shear_constant
  use udar_hydro, only: dilatational_speed2, step_shear_modulus, element_shear_moduli, tangent_bulk_modulus, &
      step_volumetric_share
  use udar_element_shared, only: element_block_t, pass_outcome_t, block_volume_ratios, material_update, &
      material_finish, block_nodes_done, add_block_ticks, block_ratios_done, begin_update_pass, end_update_pass
  implicit none
  private
  public :: tri_element_volumes, tri_element_update, tri_element_forces_averaged, tri_element_stiffness_bounds, &
            tri_element_altitudes, tri_current_volume, tri_cell_volume

  integer, parameter :: ld = block_size
  real(rk), parameter :: two_pi = 2*pi

contains

  !> The owned nodes' volume ratios J_a = V_a/Vref_a, V_a a third of each
  !> incident triangle's volume, as element_volumes does in 3D.
  subroutine tri_element_volumes(dom)
    type(domain_t), intent(inout) :: dom
    real(rk) :: area(ld), rbar(ld), vol(ld), grad(ld,3,2)
    integer :: b, n, i, c, first, last, nb
    integer(i8) :: tick0
    dom%nd_j(1:dom%n_owned_nodes) = 0.0_rk
    do b = 1, dom%n_blocks
      if (dom%time_blocks) call system_clock(tick0)
      call block_geometry(dom, b, first, last, nb, area, rbar, vol, grad)
      do i = 1, nb
        if (dom%el_state(first+i-1) == el_eroded) cycle
        do c = 1, 3
          n = dom%el_conn(first+i-1,c)
          if (n <= dom%n_owned_nodes) dom%nd_j(n) = dom%nd_j(n) + vol(i)
        end do
      end do
      call block_ratios_done(dom, b)
      if (dom%time_blocks) call add_block_ticks(dom, b, tick0)
    end do
  end subroutine

  !> Stress update of every triangle over dt with the velocities v(n+1/2)
  !> on the geometry x(n+1), as element_update in 3D (same arguments, same
  !> meaning): the 2D strain rates (rr, zz, hoop, rz) go to the material
  !> update in the places of (xx, yy, zz, xy), the spin w_rz in that of w_xy.
  subroutine tri_element_update(dom, dt, bad_elem, bad_j, n_eroded, eroded_any, dt_stable, dt_node)
    type(domain_t), intent(inout) :: dom
    real(rk), intent(in) :: dt
    integer, intent(out) :: bad_elem, bad_j, n_eroded(erode_reasons)
    logical, intent(out) :: eroded_any
    real(rk), intent(out) :: dt_stable
    integer, intent(out) :: dt_node
    real(rk) :: ve(ld,3,2), grad(ld,3,2), fe(ld,3,2), area(ld), rbar(ld), free_r(ld)
    type(element_block_t) :: eb
    type(pass_outcome_t) :: out
    logical :: axi
    integer :: b, i, nb, first, last
    integer(i8) :: tick0
    axi = dom%geometry == geometry_axisymmetric
    call begin_update_pass(dom)
    do b = 1, dom%n_blocks
      if (dom%time_blocks) call system_clock(tick0)
      call block_geometry(dom, b, first, last, nb, area, rbar, eb%vol, grad, free_r)
      call gather_block(dom, dom%nd_v, first, nb, ve)
      call tri_smallest_altitude(ld, nb, grad, eb%h)
      eb%d(1:nb,5:6) = 0.0_rk
      eb%w(1:nb,2:3) = 0.0_rk
      call tri_velocity_gradient(ld, nb, axi, ve, grad, rbar, eb%d, eb%w(:,1))
      call block_volume_ratios(dom, first, nb, eb)
      call material_update(dom, first, nb, dt, eb, out)
      ! its stiffness bound with the triangle's volumetric share (theory.md 14)
      if (dom%mat(dom%el_mat(first))%shear_model == shear_constant) then
        call tri_stiffness_bound(ld, nb, axi, eb%vol, rbar, grad, free_r, eb%bulk, &
                                 step_shear_modulus(dom%mat(dom%el_mat(first))), volumetric_share(dom), eb%lam)
      else
        call element_shear_moduli(dom%mat(dom%el_mat(first)), nb, eb%p, dom%el_temp(first:last), eb%j_new, eb%g)
        call tri_stiffness_bound(ld, nb, axi, eb%vol, rbar, grad, free_r, eb%bulk, 0.0_rk, volumetric_share(dom), &
                                 eb%lam, eb%g)
      end if
      call material_finish(dom, first, nb, dt, eb, out)
      call tri_internal_forces(ld, nb, axi, eb%vol, area, grad, eb%s, eb%p_app, fe)
      do i = 1, nb
        if (eb%gone(i)) fe(i,:,:) = 0.0_rk
      end do
      call add_forces(dom, first, nb, fe, dom%el_vol0(first:last), eb%p_node, dom%el_k(first:last))
      call block_nodes_done(dom, b, out)
      if (dom%time_blocks) call add_block_ticks(dom, b, tick0)
    end do
    call end_update_pass(out, bad_elem, bad_j, n_eroded, eroded_any, dt_stable, dt_node)
  end subroutine

  !> The nodal pressures' forces: each triangle's share of them, the mean of
  !> its nodes' averaged pressures, as a pressure in the element's forces.
  subroutine tri_element_forces_averaged(dom)
    type(domain_t), intent(inout) :: dom
    real(rk) :: p_bar(ld), fe(ld,3,2), area(ld), rbar(ld), vol(ld), grad(ld,3,2)
    real(rk), parameter :: no_deviator(ld,4) = 0.0_rk
    integer :: b, i, e, nb, first, last
    integer(i8) :: tick0
    do b = 1, dom%n_blocks
      if (dom%time_blocks) call system_clock(tick0)
      call block_geometry(dom, b, first, last, nb, area, rbar, vol, grad)
      do i = 1, nb
        e = first + i - 1
        p_bar(i) = dom%corner_share*(dom%nd_p(dom%el_conn(e,1)) + dom%nd_p(dom%el_conn(e,2)) &
                                     + dom%nd_p(dom%el_conn(e,3)))
        if (dom%el_state(e) == el_eroded) p_bar(i) = 0.0_rk
      end do
      call tri_internal_forces(ld, nb, dom%geometry == geometry_axisymmetric, vol, area, grad, no_deviator, p_bar, fe)
      call add_forces(dom, first, nb, fe)
      if (dom%time_blocks) call add_block_ticks(dom, b, tick0)
    end do
  end subroutine

  !> The stiffness bounds el_k of the current state without advancing it
  !> (start-up and restart: no viscosity).
  subroutine tri_element_stiffness_bounds(dom)
    type(domain_t), intent(inout) :: dom
    real(rk) :: area(ld), rbar(ld), vol(ld), grad(ld,3,2), c2(ld), bulk(ld), lam(ld), g, free_r(ld), g_el(ld)
    integer :: b, nb, first, last
    do b = 1, dom%n_blocks
      call block_geometry(dom, b, first, last, nb, area, rbar, vol, grad, free_r)
      associate (mat => dom%mat(dom%el_mat(first)))
        g = step_shear_modulus(mat)
        call dilatational_speed2(mat, nb, dom%el_j(first:last), dom%el_p(first:last), dom%el_mass(first:last), vol, c2)
        bulk(1:nb) = tangent_bulk_modulus(c2(1:nb), dom%el_mass(first:last)/vol(1:nb), 4.0_rk/3.0_rk*g)
        if (mat%shear_model == shear_constant) then
          call tri_stiffness_bound(ld, nb, dom%geometry == geometry_axisymmetric, vol, rbar, grad, free_r, bulk, g, &
                                   volumetric_share(dom), lam)
        else
          call element_shear_moduli(mat, nb, dom%el_p(first:last), dom%el_temp(first:last), dom%el_j(first:last), g_el)
          call tri_stiffness_bound(ld, nb, dom%geometry == geometry_axisymmetric, vol, rbar, grad, free_r, bulk, 0.0_rk, &
                                   volumetric_share(dom), lam, g_el)
        end if
      end associate
      dom%el_k(first:last) = merge(0.0_rk, lam(1:nb), dom%el_state(first:last) == el_eroded)
    end do
  end subroutine

  !> Smallest altitude of every triangle (huge for eroded ones).
  subroutine tri_element_altitudes(dom)
    type(domain_t), intent(inout) :: dom
    real(rk) :: area(ld), rbar(ld), vol(ld), grad(ld,3,2), h(ld)
    integer :: b, nb, first, last
    do b = 1, dom%n_blocks
      call block_geometry(dom, b, first, last, nb, area, rbar, vol, grad)
      call tri_smallest_altitude(ld, nb, grad, h)
      dom%el_h(first:last) = merge(huge(1.0_rk), h(1:nb), dom%el_state(first:last) == el_eroded)
    end do
  end subroutine

  !> Volume of triangle e at the current coordinates.
  real(rk) function tri_current_volume(dom, e) result(v)
    type(domain_t), intent(in) :: dom
    integer, intent(in) :: e
    real(rk) :: area(ld), rbar(ld), vol(ld), grad(ld,3,2), xe(ld,3,2)
    call gather_block(dom, dom%nd_x, e, 1, xe)
    call volumes(dom%geometry, 1, xe, area, rbar, vol, grad)
    v = vol(1)
  end function

  !> Volume (per revolution or per metre) of the triangle with corners
  !> x(3,3) (columns the corners' coordinates): the mesh set-up's.
  real(rk) function tri_cell_volume(geometry, x) result(v)
    integer, intent(in) :: geometry
    real(rk), intent(in) :: x(3,3)
    real(rk) :: area(ld), rbar(ld), vol(ld), grad(ld,3,2), xe(ld,3,2)
    xe(1,:,:) = transpose(x(1:2,:))
    call volumes(geometry, 1, xe, area, rbar, vol, grad)
    v = vol(1)
  end function

  !> The share of the volumetric stiffness the triangles' step counts:
  !> 1 plain, the triangle's patch share beyond beta for the nodal-averaged forms.
  pure real(rk) function volumetric_share(dom) result(phi)
    type(domain_t), intent(in) :: dom
    phi = step_volumetric_share(dom%anti_locking, dom%stab_beta_large, tri_patch_share)
  end function

  !> Geometry of block b at the current coordinates; when asked, free_r:
  !> how many corners of each element are off the axis (r > 0: the axis
  !> nodes never leave it), for the stiffness bound.
  subroutine block_geometry(dom, b, first, last, nb, area, rbar, vol, grad, free_r)
    type(domain_t), intent(in) :: dom
    integer, intent(in) :: b
    integer, intent(out) :: first, last, nb
    real(rk), intent(inout) :: area(ld), rbar(ld), vol(ld), grad(ld,3,2)
    real(rk), intent(inout), optional :: free_r(ld)
    real(rk) :: xe(ld,3,2)
    integer :: i
    first = dom%blk_first(b)
    last = dom%blk_last(b)
    nb = last - first + 1
    call gather_block(dom, dom%nd_x, first, nb, xe)
    call volumes(dom%geometry, nb, xe, area, rbar, vol, grad)
    if (present(free_r)) then
      do i = 1, nb
        free_r(i) = merge(1.0_rk, 0.0_rk, xe(i,1,1) > 0.0_rk) + merge(1.0_rk, 0.0_rk, xe(i,2,1) > 0.0_rk) &
                  + merge(1.0_rk, 0.0_rk, xe(i,3,1) > 0.0_rk)
      end do
    end if
  end subroutine

  !> tri_geometry with the volume and area of a full revolution
  !> (axisymmetric: the kernel's are per radian) or per metre.
  subroutine volumes(geometry, nb, xe, area, rbar, vol, grad)
    integer, intent(in) :: geometry, nb
    real(rk), intent(in) :: xe(ld,3,2)
    real(rk), intent(inout) :: area(ld), rbar(ld), vol(ld), grad(ld,3,2)
    call tri_geometry(ld, nb, geometry == geometry_axisymmetric, xe, area, rbar, vol, grad)
    if (geometry == geometry_axisymmetric) then
      area(1:nb) = two_pi*area(1:nb)
      vol(1:nb) = two_pi*vol(1:nb)
    end if
  end subroutine

  !> The in-plane components of nodal vectors a(3,n) of the nb triangles
  !> from first on, into a block (ld,3,2).
  subroutine gather_block(dom, a, first, nb, block)
    type(domain_t), intent(in) :: dom
    real(rk), intent(in) :: a(3,*)
    integer, intent(in) :: first, nb
    real(rk), intent(inout) :: block(ld,3,2)
    integer :: i, c, node
    do i = 1, nb
      do c = 1, 3
        node = dom%el_conn(first+i-1, c)
        block(i,c,1) = a(1,node); block(i,c,2) = a(2,node)
      end do
    end do
  end subroutine

  !> Block forces (ld,3,2) added to the owned nodes' in-plane forces, and
  !> when given the nodes' sums of v0 p and of the stiffness bounds, element
  !> after element in ascending id (as the 3D add_forces).
  subroutine add_forces(dom, first, nb, fe, v0, p, k_el)
    type(domain_t), intent(inout) :: dom
    integer, intent(in) :: first, nb
    real(rk), intent(in) :: fe(ld,3,2)
    real(rk), intent(in), optional :: v0(nb), p(ld), k_el(nb)
    integer :: a, i, n
    do i = 1, nb
      do a = 1, 3
        n = dom%el_conn(first+i-1, a)
        if (n > dom%n_owned_nodes) cycle
        dom%nd_f(1,n) = dom%nd_f(1,n) + fe(i,a,1)
        dom%nd_f(2,n) = dom%nd_f(2,n) + fe(i,a,2)
        if (present(k_el)) then
          dom%nd_p(n) = dom%nd_p(n) + v0(i)*p(i)
          dom%nd_k(n) = dom%nd_k(n) + k_el(i)
        end if
      end do
    end do
  end subroutine
end module udar_tri_driver
