!> Element passes of one cycle, over vectorized blocks: gather nodal data,
!> call the pure kernels, keep element state. Nodal averages (anti-locking)
!> and force assembly run over the node->element lists in ascending element
!> id, so every sum has one fixed order whatever the partition.
module udar_element_driver
  use udar_kinds, only: rk
  use udar_domain, only: domain_t, block_size
  use udar_config, only: material_cfg_t, eos_linear, eos_mie_gruneisen, strength_none
  use udar_tet4, only: tet_gradients, tet_velocity_gradient, tet_internal_forces, tet_volume
  use udar_eos, only: eos_linear_ab, eos_linear_c2, eos_mie_gruneisen_ab, eos_mie_gruneisen_c2
  use udar_strength, only: rotate_deviator, deviatoric_update
  implicit none
  private
  public :: element_volumes, nodal_volumes, element_update, nodal_pressures, &
            element_forces_averaged, assemble_forces, element_stable_dt

contains

  !> Current element volumes from the nodal coordinates.
  subroutine element_volumes(dom)
    type(domain_t), intent(inout) :: dom
    real(rk) :: xe(4,3)
    integer :: e, a
    do e = 1, dom%n_elems
      do a = 1, 4
        xe(a,:) = dom%nd_x(dom%el_conn(e,a),:)
      end do
      dom%el_vol(e) = tet_volume(xe)
    end do
  end subroutine

  !> Nodal volume: a quarter of each incident element (Bonet and Burton 1998).
  subroutine nodal_volumes(dom)
    type(domain_t), intent(inout) :: dom
    integer :: n, k
    real(rk) :: acc
    do n = 1, dom%n_nodes
      acc = 0.0_rk
      do k = dom%nd_el_ptr(n), dom%nd_el_ptr(n+1) - 1
        acc = acc + dom%el_vol(dom%nd_el(k))
      end do
      dom%nd_vol(n) = 0.25_rk*acc
    end do
  end subroutine

  !> Nodal pressure: reference-volume-weighted mean of the incident elements'
  !> EOS pressures; the weights make the averaged forces the exact gradient of
  !> the averaged-volume energy.
  subroutine nodal_pressures(dom)
    type(domain_t), intent(inout) :: dom
    integer :: n, k, e
    real(rk) :: acc
    do n = 1, dom%n_nodes
      acc = 0.0_rk
      do k = dom%nd_el_ptr(n), dom%nd_el_ptr(n+1) - 1
        e = dom%nd_el(k)
        acc = acc + dom%el_vol0(e)*dom%el_p(e)
      end do
      dom%nd_p(n) = 0.25_rk*acc/dom%nd_vol0(n)
    end do
  end subroutine

  !> Stress update of every element over dt with the velocities v(n+1/2) on
  !> the geometry x(n+1); forces too unless anti-locking needs the nodal
  !> pressures first. Returns the smallest stable time step and the first
  !> element (lowest id) with a non-positive volume, or 0.
  subroutine element_update(dom, dt, dt_stable, bad_elem)
    type(domain_t), intent(inout) :: dom
    real(rk), intent(in) :: dt
    real(rk), intent(out) :: dt_stable
    integer, intent(out) :: bad_elem
    real(rk) :: xe(block_size,4,3), ve(block_size,4,3), grad(block_size,4,3), fe(block_size,4,3)
    real(rk) :: vol(block_size), h(block_size), d(block_size,6), w(block_size,3), p_app(block_size)
    real(rk) :: sb(block_size,6), s6(6), d6(6), w3(3)
    integer :: b, i, e, a, nb, first, node, k
    dt_stable = huge(1.0_rk)
    bad_elem = 0
    do b = 1, dom%n_blocks
      first = dom%blk_first(b)
      nb = dom%blk_last(b) - first + 1
      do a = 1, 4
        do i = 1, nb
          node = dom%el_conn(first+i-1, a)
          xe(i,a,:) = dom%nd_x(node,:)
          ve(i,a,:) = dom%nd_v(node,:)
        end do
      end do
      call tet_gradients(block_size, nb, xe, vol, grad, h)
      call tet_velocity_gradient(block_size, nb, ve, grad, d, w)
      associate (mat => dom%mat(dom%el_mat(first)))
        do i = 1, nb
          e = first + i - 1
          p_app(i) = 0.0_rk
          if (vol(i) <= 0.0_rk) then
            if (bad_elem == 0) bad_elem = e
            sb(i,:) = 0.0_rk
            cycle
          end if
          s6 = dom%el_s(e,:); d6 = d(i,:); w3 = w(i,:)
          call material_update(mat, dom, e, dt, vol(i), h(i), d6, w3, s6, p_app(i), dt_stable)
          dom%el_s(e,:) = s6; sb(i,:) = s6
        end do
      end associate
      if (dom%anti_locking) then
        do k = 1, 3
          do a = 1, 4
            dom%el_grad(first:first+nb-1,a,k) = grad(1:nb,a,k)
          end do
        end do
      else
        call tet_internal_forces(block_size, nb, vol, grad, sb, p_app, fe)
        call store_forces(dom, first, nb, fe)
      end if
      dom%el_vol(first:first+nb-1) = vol(1:nb)
    end do
  end subroutine

  !> State update of element e: rotation, strength, viscosity, EOS and energy.
  !> p_app returns the pressure its forces see when there is no averaging.
  subroutine material_update(mat, dom, e, dt, vol, h, d, w, s, p_app, dt_stable)
    type(material_cfg_t), intent(in) :: mat
    type(domain_t), intent(inout) :: dom
    integer, intent(in) :: e
    real(rk), intent(in) :: dt, vol, h, d(6), w(3)
    real(rk), intent(inout) :: s(6), dt_stable
    real(rk), intent(out) :: p_app
    real(rk) :: j_new, j_old, rho, trd, mass, d_eps_p, w_dev, w_pl, c2, c, q, dv, e_star, a, bcoef, eq, qdt
    integer :: k
    mass = dom%el_mass(e)
    rho = mass/vol
    trd = d(1) + d(2) + d(3)
    if (dom%anti_locking) then
      j_new = 0.0_rk
      do k = 1, 4
        j_new = j_new + dom%nd_vol(dom%el_conn(e,k))/dom%nd_vol0(dom%el_conn(e,k))
      end do
      j_new = 0.25_rk*j_new
    else
      j_new = vol/dom%el_vol0(e)
    end if
    j_old = dom%el_j(e)
    ! deviatoric part (Jaumann rotation, trial step, radial return)
    if (mat%strength /= strength_none) call rotate_deviator(dt, w, s)
    call deviatoric_update(mat, dt, d, dom%el_temp(e), s, dom%el_eps_p(e), d_eps_p, w_dev, w_pl)
    ! sound speed at the old pressure, for the viscosity and the time step
    c2 = sound_speed2(mat, j_old, dom%el_p(e), rho)
    c = sqrt(c2)
    ! linear + quadratic bulk viscosity in compression only
    if (trd < 0.0_rk) then
      q = rho*h*(dom%q_quadratic*h*trd*trd - dom%q_linear*c*trd)
      eq = dom%q_linear*c + dom%q_quadratic*h*abs(trd)
    else
      q = 0.0_rk
      eq = 0.0_rk
    end if
    ! energy: e(n+1) = e* - dv/2 (A + B e(n+1)), solved exactly (p linear in e)
    dv = (j_new - j_old)/mat%rho0
    qdt = q*trd*dt*vol/mass
    e_star = dom%el_e(e) + w_dev*vol/mass - qdt - 0.5_rk*dom%el_p(e)*dv
    select case (mat%eos)
    case (eos_mie_gruneisen)
      call eos_mie_gruneisen_ab(mat%rho0, mat%c0, mat%s, mat%gamma0, j_new, a, bcoef)
    case default
      call eos_linear_ab(mat%bulk_modulus, j_new, a, bcoef)
    end select
    dom%el_e(e) = (e_star - 0.5_rk*dv*a)/(1.0_rk + 0.5_rk*dv*bcoef)
    dom%el_p(e) = a + bcoef*dom%el_e(e)
    dom%el_q(e) = q
    dom%el_j(e) = j_new
    if (w_pl > 0.0_rk) then
      dom%el_wp(e) = dom%el_wp(e) + w_pl*vol/mass
      if (mat%specific_heat > 0.0_rk) &
        dom%el_temp(e) = dom%el_temp(e) + mat%taylor_quinney*w_pl/(rho*mat%specific_heat)
    end if
    p_app = dom%el_p(e) + q
    ! stable step h / (Q + sqrt(Q^2 + c^2)) with Q the viscosity's own speed
    dt_stable = min(dt_stable, h/(eq + sqrt(eq*eq + c2)))
  end subroutine

  !> Square of the dilatational wave speed: bulk sound speed plus 4G/(3 rho).
  pure real(rk) function sound_speed2(mat, j, p, rho) result(c2)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: j, p, rho
    select case (mat%eos)
    case (eos_mie_gruneisen)
      c2 = eos_mie_gruneisen_c2(mat%rho0, mat%c0, mat%s, mat%gamma0, j, p)
    case default
      c2 = eos_linear_c2(mat%bulk_modulus, mat%rho0)
    end select
    if (mat%strength /= strength_none) c2 = c2 + 4.0_rk*mat%shear_modulus/(3.0_rk*rho)
  end function

  !> Stable step of the current state without advancing it (start-up).
  subroutine element_stable_dt(dom, dt_stable)
    type(domain_t), intent(in) :: dom
    real(rk), intent(out) :: dt_stable
    real(rk) :: xe(block_size,4,3), grad(block_size,4,3), vol(block_size), h(block_size), c2
    integer :: b, i, a, nb, first, e
    dt_stable = huge(1.0_rk)
    do b = 1, dom%n_blocks
      first = dom%blk_first(b)
      nb = dom%blk_last(b) - first + 1
      do a = 1, 4
        do i = 1, nb
          xe(i,a,:) = dom%nd_x(dom%el_conn(first+i-1, a),:)
        end do
      end do
      call tet_gradients(block_size, nb, xe, vol, grad, h)
      do i = 1, nb
        e = first + i - 1
        c2 = sound_speed2(dom%mat(dom%el_mat(e)), dom%el_j(e), dom%el_p(e), dom%el_mass(e)/vol(i))
        dt_stable = min(dt_stable, h(i)/sqrt(c2))
      end do
    end do
  end subroutine

  !> Forces with the element pressure replaced by the mean of its nodes'
  !> averaged pressures (plus its own viscosity).
  subroutine element_forces_averaged(dom)
    type(domain_t), intent(inout) :: dom
    real(rk) :: p_app(block_size), fe(block_size,4,3), vol(block_size), grad(block_size,4,3), sb(block_size,6)
    integer :: b, i, e, nb, first, a, k
    do b = 1, dom%n_blocks
      first = dom%blk_first(b)
      nb = dom%blk_last(b) - first + 1
      do i = 1, nb
        e = first + i - 1
        p_app(i) = 0.25_rk*(dom%nd_p(dom%el_conn(e,1)) + dom%nd_p(dom%el_conn(e,2)) &
                 + dom%nd_p(dom%el_conn(e,3)) + dom%nd_p(dom%el_conn(e,4))) + dom%el_q(e)
        vol(i) = dom%el_vol(e)
      end do
      do k = 1, 6
        sb(1:nb,k) = dom%el_s(first:first+nb-1,k)
      end do
      do k = 1, 3
        do a = 1, 4
          grad(1:nb,a,k) = dom%el_grad(first:first+nb-1,a,k)
        end do
      end do
      call tet_internal_forces(block_size, nb, vol, grad, sb, p_app, fe)
      call store_forces(dom, first, nb, fe)
    end do
  end subroutine

  subroutine store_forces(dom, first, nb, fe)
    type(domain_t), intent(inout) :: dom
    integer, intent(in) :: first, nb
    real(rk), intent(in) :: fe(block_size,4,3)
    integer :: a, k
    do k = 1, 3
      do a = 1, 4
        dom%el_f(first:first+nb-1,a,k) = fe(1:nb,a,k)
      end do
    end do
  end subroutine

  !> Nodal forces: element contributions summed in ascending element id.
  subroutine assemble_forces(dom)
    type(domain_t), intent(inout) :: dom
    integer :: n, k
    real(rk) :: fx, fy, fz
    do n = 1, dom%n_nodes
      fx = 0.0_rk; fy = 0.0_rk; fz = 0.0_rk
      do k = dom%nd_el_ptr(n), dom%nd_el_ptr(n+1) - 1
        fx = fx + dom%el_f(dom%nd_el(k), dom%nd_el_corner(k), 1)
        fy = fy + dom%el_f(dom%nd_el(k), dom%nd_el_corner(k), 2)
        fz = fz + dom%el_f(dom%nd_el(k), dom%nd_el_corner(k), 3)
      end do
      dom%nd_f(n,1) = fx; dom%nd_f(n,2) = fy; dom%nd_f(n,3) = fz
    end do
  end subroutine
end module udar_element_driver
