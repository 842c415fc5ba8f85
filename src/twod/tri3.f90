!> The 2D three-node triangle (issue 14, in progress: not yet driven by a
!> 2D solver): geometry, strain rate and internal nodal forces, plane
!> strain or axisymmetric, block-wise (element index innermost) like the
!> 3D tet4 kernels. Coordinates (r, z) with r >= 0 the radius and z the
!> axis (axisymmetric), or (x, y) (plane strain). Axisymmetric quantities
!> are per radian: the element's volume is rbar A, rbar the mean radius of
!> its corners and A its area (doc/theory.md section 14). Pure kernels:
!> no state, no I/O.
module udar_tri3
  use udar_kinds, only: rk
  implicit none
  private
  public :: tri_geometry, tri_smallest_altitude, tri_velocity_gradient, tri_internal_forces, tri_stiffness_bound, &
            tri_patch_share

  !> The share of a nodal-averaged triangle's volumetric stiffness the
  !> nodal time step counts beyond the element's own (step_volumetric_share;
  !> the tetrahedron's is 1/6). Measured (unit/test_stable_step_2d): with
  !> 1/4 the assembled limit is at least 1.13 times the nodal step on every
  !> mesh tried up to nu = 0.49 (1/6 leaves the 'nodal' triangle at 0.93
  !> towards nu = 0.5).
  real(rk), parameter :: tri_patch_share = 0.25_rk

contains

  !> Area (positive for corners counter-clockwise in the (r, z) plane),
  !> mean radius rbar, volume vol (axisymmetric: rbar A per radian; plane
  !> strain: A per unit thickness) and the gradients dN_a/dr, dN_a/dz of
  !> the first nb elements of a block, x(ld,3,2) their corners' coordinates.
  pure subroutine tri_geometry(ld, nb, axisymmetric, x, area, rbar, vol, grad)
    integer, intent(in) :: ld, nb
    logical, intent(in) :: axisymmetric
    real(rk), intent(in) :: x(ld,3,2)
    real(rk), intent(inout) :: area(nb), rbar(nb), vol(nb), grad(ld,3,2)
    !> |2A| below this share of the longest edge squared: no area (gradients 0)
    real(rk), parameter :: collapsed = 1e-12_rk
    real(rk) :: two_a, r, edge2
    integer :: i
    do i = 1, nb
      two_a = (x(i,2,1) - x(i,1,1))*(x(i,3,2) - x(i,1,2)) - (x(i,3,1) - x(i,1,1))*(x(i,2,2) - x(i,1,2))
      area(i) = 0.5_rk*two_a
      rbar(i) = (x(i,1,1) + x(i,2,1) + x(i,3,1))/3.0_rk
      vol(i) = merge(rbar(i)*area(i), area(i), axisymmetric)
      ! an inverted element keeps finite numbers (a driver stops on area <= 0),
      ! and so does a collapsed one (an element gone from the calculation
      ! whose massless corners came together: finite, and 0)
      edge2 = max((x(i,2,1) - x(i,1,1))**2 + (x(i,2,2) - x(i,1,2))**2, (x(i,3,1) - x(i,2,1))**2 + (x(i,3,2) - x(i,2,2))**2, &
                  (x(i,1,1) - x(i,3,1))**2 + (x(i,1,2) - x(i,3,2))**2)
      r = 0.0_rk
      if (abs(two_a) > collapsed*edge2) r = 1.0_rk/merge(two_a, 1.0_rk, abs(two_a) > collapsed*edge2)
      grad(i,1,1) = (x(i,2,2) - x(i,3,2))*r; grad(i,1,2) = (x(i,3,1) - x(i,2,1))*r
      grad(i,2,1) = (x(i,3,2) - x(i,1,2))*r; grad(i,2,2) = (x(i,1,1) - x(i,3,1))*r
      grad(i,3,1) = (x(i,1,2) - x(i,2,2))*r; grad(i,3,2) = (x(i,2,1) - x(i,1,1))*r
    end do
  end subroutine

  !> Smallest altitude of the first nb elements from their gradients: the
  !> altitude over the edge opposite corner a is 1/|grad N_a| (the length
  !> the artificial viscosity and the element's own step take, as in 3D).
  pure subroutine tri_smallest_altitude(ld, nb, grad, h)
    integer, intent(in) :: ld, nb
    real(rk), intent(in) :: grad(ld,3,2)
    real(rk), intent(inout) :: h(nb)
    integer :: i
    do i = 1, nb
      h(i) = 1.0_rk/sqrt(max(grad(i,1,1)**2 + grad(i,1,2)**2, grad(i,2,1)**2 + grad(i,2,2)**2, &
                             grad(i,3,1)**2 + grad(i,3,2)**2, tiny(1.0_rk)))
    end do
  end subroutine

  !> Strain rate d = (rr, zz, hoop, rz) and spin w = (dv_r/dz - dv_z/dr)/2
  !> of the first nb elements from the corner velocities v(ld,3,2). The
  !> hoop rate is the mean radial velocity over the mean radius (the
  !> centroid's v_r / r: exact for v_r linear in r, so a uniform radial
  !> expansion v_r = a r gives d_rr = d_hoop = a); 0 in plane strain.
  pure subroutine tri_velocity_gradient(ld, nb, axisymmetric, v, grad, rbar, d, w)
    integer, intent(in) :: ld, nb
    logical, intent(in) :: axisymmetric
    real(rk), intent(in) :: v(ld,3,2), grad(ld,3,2), rbar(nb)
    real(rk), intent(inout) :: d(ld,4), w(nb)
    real(rk) :: lrr, lrz, lzr, lzz
    integer :: i
    do i = 1, nb
      lrr = v(i,1,1)*grad(i,1,1) + v(i,2,1)*grad(i,2,1) + v(i,3,1)*grad(i,3,1)
      lrz = v(i,1,1)*grad(i,1,2) + v(i,2,1)*grad(i,2,2) + v(i,3,1)*grad(i,3,2)
      lzr = v(i,1,2)*grad(i,1,1) + v(i,2,2)*grad(i,2,1) + v(i,3,2)*grad(i,3,1)
      lzz = v(i,1,2)*grad(i,1,2) + v(i,2,2)*grad(i,2,2) + v(i,3,2)*grad(i,3,2)
      d(i,1) = lrr
      d(i,2) = lzz
      d(i,3) = 0.0_rk
      ! (rbar = 0 only for an element gone from the calculation whose
      ! corners, massless once it became a particle, all lie on the axis)
      if (axisymmetric .and. rbar(i) > 0.0_rk) &
        d(i,3) = (v(i,1,1) + v(i,2,1) + v(i,3,1))/(3.0_rk*merge(rbar(i), 1.0_rk, rbar(i) > 0.0_rk))
      d(i,4) = 0.5_rk*(lrz + lzr)
      w(i) = 0.5_rk*(lrz - lzr)
    end do
  end subroutine

  !> Internal nodal forces f(ld,3,2) of the stress sigma = s - p I, s the
  !> deviator (rr, zz, hoop, rz), p the pressure:
  !>   f_a,r = -vol (sigma_rr dN_a/dr + sigma_rz dN_a/dz) - A sigma_hoop / 3,
  !>   f_a,z = -vol (sigma_rz dN_a/dr + sigma_zz dN_a/dz),
  !> the hoop term only axisymmetric. The transpose of
  !> tri_velocity_gradient: sum_a f_a . v_a = -vol sigma : d exactly, so the
  !> forces' work is the stress power (energy conservation), and a uniform
  !> stress with sigma_rr = sigma_hoop, sigma_rz = 0 (in equilibrium) leaves
  !> every interior node without force.
  pure subroutine tri_internal_forces(ld, nb, axisymmetric, vol, area, grad, s, p, f)
    integer, intent(in) :: ld, nb
    logical, intent(in) :: axisymmetric
    real(rk), intent(in) :: vol(nb), area(nb), grad(ld,3,2), s(ld,4), p(nb)
    real(rk), intent(inout) :: f(ld,3,2)
    real(rk) :: srr, szz, shoop, hoop
    integer :: i, a
    do a = 1, 3
      do i = 1, nb
        srr = s(i,1) - p(i); szz = s(i,2) - p(i); shoop = s(i,3) - p(i)
        hoop = 0.0_rk
        if (axisymmetric) hoop = area(i)*shoop/3.0_rk
        f(i,a,1) = -vol(i)*(srr*grad(i,a,1) + s(i,4)*grad(i,a,2)) - hoop
        f(i,a,2) = -vol(i)*(s(i,4)*grad(i,a,1) + szz*grad(i,a,2))
      end do
    end do
  end subroutine

  !> An upper bound of the largest eigenvalue of the element's isotropic
  !> elastic stiffness (bulk modulus k(i), shear modulus g; per radian
  !> axisymmetric), for the nodal time step as in 3D (theory.md sections 9
  !> and 14), with the radial velocity of the corners on the axis held at
  !> 0 (the axis condition): free_r(i) of the corners move radially. With
  !> S = sum_a grad N_a grad N_a^T (2 x 2), L the in-plane velocity
  !> gradient, D = sum_a |u_a|^2 and the hoop rate's weight
  !> eta = free_r/(9 rbar^2) (the hoop rate is the free corners' radial
  !> velocities over 3 rbar; 0 in plane strain):
  !>   (tr L)^2 <= tr S D,  |sym L|^2 <= s_max D,  d_hoop^2 <= eta D,
  !> so with lambda = k - 2g/3 >= 0
  !>   u.K u <= V D (phi lambda (sqrt(tr S) + sqrt(eta))^2 + 2 g (s_max + eta)),
  !> phi the share of the volumetric part the step counts, as in
  !> tet_stiffness_bound (step_volumetric_share): with phi = 1 a bound of
  !> the plain element's stiffness; below 1 an estimate for the
  !> nodal-averaged elements, whose averaged part acts over the nodal patch.
  pure subroutine tri_stiffness_bound(ld, nb, axisymmetric, vol, rbar, grad, free_r, k, g, phi, lam, g_el)
    integer, intent(in) :: ld, nb
    logical, intent(in) :: axisymmetric
    real(rk), intent(in) :: vol(nb), rbar(nb), grad(ld,3,2), free_r(nb), k(nb), g, phi
    real(rk), intent(inout) :: lam(nb)
    !> each element's shear modulus, where it depends on the state (then g is not used)
    real(rk), intent(in), optional :: g_el(nb)
    real(rk) :: srr, szz, srz, s_max, eta
    integer :: i
    ! two loops on purpose: the constant-G one is the code every constant-G
    ! deck was measured and baselined with (G as an array changed its last
    ! bits by code generation: design.md D13); the per-element one serves
    ! state-dependent shear moduli only
    if (present(g_el)) then
      do i = 1, nb
        srr = grad(i,1,1)**2 + grad(i,2,1)**2 + grad(i,3,1)**2
        szz = grad(i,1,2)**2 + grad(i,2,2)**2 + grad(i,3,2)**2
        srz = grad(i,1,1)*grad(i,1,2) + grad(i,2,1)*grad(i,2,2) + grad(i,3,1)*grad(i,3,2)
        s_max = 0.5_rk*(srr + szz) + sqrt(0.25_rk*(srr - szz)**2 + srz**2)
        eta = 0.0_rk
        if (axisymmetric .and. rbar(i) > 0.0_rk) eta = free_r(i)/(9.0_rk*merge(rbar(i), 1.0_rk, rbar(i) > 0.0_rk)**2)
        lam(i) = abs(vol(i))*(phi*max(k(i) - 2.0_rk/3.0_rk*g_el(i), 0.0_rk)*(sqrt(srr + szz) + sqrt(eta))**2 &
                              + 2.0_rk*g_el(i)*(s_max + eta))
      end do
      return
    end if
    do i = 1, nb
      srr = grad(i,1,1)**2 + grad(i,2,1)**2 + grad(i,3,1)**2
      szz = grad(i,1,2)**2 + grad(i,2,2)**2 + grad(i,3,2)**2
      srz = grad(i,1,1)*grad(i,1,2) + grad(i,2,1)*grad(i,2,2) + grad(i,3,1)*grad(i,3,2)
      s_max = 0.5_rk*(srr + szz) + sqrt(0.25_rk*(srr - szz)**2 + srz**2)
      eta = 0.0_rk
      if (axisymmetric .and. rbar(i) > 0.0_rk) eta = free_r(i)/(9.0_rk*merge(rbar(i), 1.0_rk, rbar(i) > 0.0_rk)**2)
      lam(i) = abs(vol(i))*(phi*max(k(i) - 2.0_rk/3.0_rk*g, 0.0_rk)*(sqrt(srr + szz) + sqrt(eta))**2 &
                            + 2.0_rk*g*(s_max + eta))
    end do
  end subroutine
end module udar_tri3
