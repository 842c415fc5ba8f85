!> Kernels of the 4-node constant-strain tetrahedron. Pure, block-wise: each
!> routine works on the first nb elements of a block, element index
!> innermost so the loops vectorize. Convention of all block kernels:
!> multi-dimensional arrays have leading dimension ld (block_size), 1-D
!> arrays are sized nb, so a contiguous section of a domain array can be
!> passed without a copy.
module udar_tet4
  use udar_kinds, only: rk
  implicit none
  private
  public :: tet_volume, tet_volumes, tet_gradients, tet_velocity_gradient, tet_internal_forces, tet_pressure_forces, &
            tet_stiffness_bound

contains

  !> Signed volume of one tetrahedron: det[x2-x1, x3-x1, x4-x1] / 6.
  pure real(rk) function tet_volume(x) result(v)
    real(rk), intent(in) :: x(4,3)
    real(rk) :: d1(3), d2(3), d3(3)
    d1 = x(2,:) - x(1,:); d2 = x(3,:) - x(1,:); d3 = x(4,:) - x(1,:)
    v = (d1(1)*(d2(2)*d3(3) - d2(3)*d3(2)) + d1(2)*(d2(3)*d3(1) - d2(1)*d3(3)) &
       + d1(3)*(d2(1)*d3(2) - d2(2)*d3(1))) / 6.0_rk
  end function

  !> tet_volume of the first nb elements of a block, the same arithmetic.
  pure subroutine tet_volumes(ld, nb, x, vol)
    integer, intent(in) :: ld, nb
    real(rk), intent(in) :: x(ld,4,3)
    real(rk), intent(inout) :: vol(nb)
    real(rk) :: d1(3), d2(3), d3(3)
    integer :: i
    do i = 1, nb
      d1 = x(i,2,:) - x(i,1,:); d2 = x(i,3,:) - x(i,1,:); d3 = x(i,4,:) - x(i,1,:)
      vol(i) = (d1(1)*(d2(2)*d3(3) - d2(3)*d3(2)) + d1(2)*(d2(3)*d3(1) - d2(1)*d3(3)) &
              + d1(3)*(d2(1)*d3(2) - d2(2)*d3(1))) / 6.0_rk
    end do
  end subroutine

  !> Volume, shape-function gradients dN_a/dx_k and g2max = max_a |grad N_a|^2
  !> (the altitude over face a is 1/|grad N_a|: smallest altitude 1/sqrt(g2max)).
  pure subroutine tet_gradients(ld, nb, x, vol, grad, g2max)
    integer, intent(in) :: ld, nb
    real(rk), intent(in) :: x(ld,4,3)
    real(rk), intent(inout) :: vol(nb), grad(ld,4,3), g2max(nb)
    real(rk) :: d1x, d1y, d1z, d2x, d2y, d2z, d3x, d3y, d3z, six_v, r, g2, gmax
    integer :: i, a
    do i = 1, nb
      d1x = x(i,2,1) - x(i,1,1); d1y = x(i,2,2) - x(i,1,2); d1z = x(i,2,3) - x(i,1,3)
      d2x = x(i,3,1) - x(i,1,1); d2y = x(i,3,2) - x(i,1,2); d2z = x(i,3,3) - x(i,1,3)
      d3x = x(i,4,1) - x(i,1,1); d3y = x(i,4,2) - x(i,1,2); d3z = x(i,4,3) - x(i,1,3)
      ! grad N2 = d2 x d3 / 6V, grad N3 = d3 x d1 / 6V, grad N4 = d1 x d2 / 6V
      grad(i,2,1) = d2y*d3z - d2z*d3y; grad(i,2,2) = d2z*d3x - d2x*d3z; grad(i,2,3) = d2x*d3y - d2y*d3x
      grad(i,3,1) = d3y*d1z - d3z*d1y; grad(i,3,2) = d3z*d1x - d3x*d1z; grad(i,3,3) = d3x*d1y - d3y*d1x
      grad(i,4,1) = d1y*d2z - d1z*d2y; grad(i,4,2) = d1z*d2x - d1x*d2z; grad(i,4,3) = d1x*d2y - d1y*d2x
      six_v = d1x*grad(i,2,1) + d1y*grad(i,2,2) + d1z*grad(i,2,3)
      vol(i) = six_v / 6.0_rk
      ! an inverted element keeps finite numbers; the driver stops on vol <= 0
      r = 1.0_rk / merge(six_v, 1.0_rk, six_v /= 0.0_rk)
      grad(i,2:4,:) = grad(i,2:4,:) * r
      grad(i,1,1) = -(grad(i,2,1) + grad(i,3,1) + grad(i,4,1))
      grad(i,1,2) = -(grad(i,2,2) + grad(i,3,2) + grad(i,4,2))
      grad(i,1,3) = -(grad(i,2,3) + grad(i,3,3) + grad(i,4,3))
      gmax = 0.0_rk
      do a = 1, 4
        g2 = grad(i,a,1)**2 + grad(i,a,2)**2 + grad(i,a,3)**2
        gmax = max(gmax, g2)
      end do
      g2max(i) = max(gmax, tiny(1.0_rk))
    end do
  end subroutine

  !> Velocity gradient L_kl = sum_a v_ak dN_a/dx_l, returned as the strain rate
  !> D (xx,yy,zz,xy,yz,zx) and the spin W (w_xy, w_yz, w_zx), W = (L - L^T)/2.
  pure subroutine tet_velocity_gradient(ld, nb, v, grad, d, w)
    integer, intent(in) :: ld, nb
    real(rk), intent(in) :: v(ld,4,3), grad(ld,4,3)
    real(rk), intent(inout) :: d(ld,6), w(ld,3)
    real(rk) :: l11, l12, l13, l21, l22, l23, l31, l32, l33
    integer :: i
    ! L_km written out: a local l(3,3) kept the block loop from vectorizing
    do i = 1, nb
      l11 = v(i,1,1)*grad(i,1,1) + v(i,2,1)*grad(i,2,1) + v(i,3,1)*grad(i,3,1) + v(i,4,1)*grad(i,4,1)
      l12 = v(i,1,1)*grad(i,1,2) + v(i,2,1)*grad(i,2,2) + v(i,3,1)*grad(i,3,2) + v(i,4,1)*grad(i,4,2)
      l13 = v(i,1,1)*grad(i,1,3) + v(i,2,1)*grad(i,2,3) + v(i,3,1)*grad(i,3,3) + v(i,4,1)*grad(i,4,3)
      l21 = v(i,1,2)*grad(i,1,1) + v(i,2,2)*grad(i,2,1) + v(i,3,2)*grad(i,3,1) + v(i,4,2)*grad(i,4,1)
      l22 = v(i,1,2)*grad(i,1,2) + v(i,2,2)*grad(i,2,2) + v(i,3,2)*grad(i,3,2) + v(i,4,2)*grad(i,4,2)
      l23 = v(i,1,2)*grad(i,1,3) + v(i,2,2)*grad(i,2,3) + v(i,3,2)*grad(i,3,3) + v(i,4,2)*grad(i,4,3)
      l31 = v(i,1,3)*grad(i,1,1) + v(i,2,3)*grad(i,2,1) + v(i,3,3)*grad(i,3,1) + v(i,4,3)*grad(i,4,1)
      l32 = v(i,1,3)*grad(i,1,2) + v(i,2,3)*grad(i,2,2) + v(i,3,3)*grad(i,3,2) + v(i,4,3)*grad(i,4,2)
      l33 = v(i,1,3)*grad(i,1,3) + v(i,2,3)*grad(i,2,3) + v(i,3,3)*grad(i,3,3) + v(i,4,3)*grad(i,4,3)
      d(i,1) = l11; d(i,2) = l22; d(i,3) = l33
      d(i,4) = 0.5_rk*(l12 + l21); d(i,5) = 0.5_rk*(l23 + l32); d(i,6) = 0.5_rk*(l31 + l13)
      w(i,1) = 0.5_rk*(l12 - l21); w(i,2) = 0.5_rk*(l23 - l32); w(i,3) = 0.5_rk*(l31 - l13)
    end do
  end subroutine

  !> Internal nodal forces f_a = -V sigma . grad N_a for the Cauchy stress
  !> sigma = s - p I, s deviatoric (xx,yy,zz,xy,yz,zx), p the applied pressure.
  pure subroutine tet_internal_forces(ld, nb, vol, grad, s, p, f)
    integer, intent(in) :: ld, nb
    real(rk), intent(in) :: vol(nb), grad(ld,4,3), s(ld,6), p(nb)
    real(rk), intent(inout) :: f(ld,4,3)
    real(rk) :: sxx, syy, szz
    integer :: i, a
    do a = 1, 4
      do i = 1, nb
        sxx = s(i,1) - p(i); syy = s(i,2) - p(i); szz = s(i,3) - p(i)
        f(i,a,1) = -vol(i)*(sxx*grad(i,a,1) + s(i,4)*grad(i,a,2) + s(i,6)*grad(i,a,3))
        f(i,a,2) = -vol(i)*(s(i,4)*grad(i,a,1) + syy*grad(i,a,2) + s(i,5)*grad(i,a,3))
        f(i,a,3) = -vol(i)*(s(i,6)*grad(i,a,1) + s(i,5)*grad(i,a,2) + szz*grad(i,a,3))
      end do
    end do
  end subroutine

  !> Internal nodal forces of a pressure p alone, f_a = V p grad N_a, from
  !> the coordinates: V grad N_a is a sixth of the cofactor vector of
  !> tet_gradients (no volume, no division).
  pure subroutine tet_pressure_forces(ld, nb, x, p, f)
    integer, intent(in) :: ld, nb
    real(rk), intent(in) :: x(ld,4,3), p(nb)
    real(rk), intent(inout) :: f(ld,4,3)
    real(rk) :: d1x, d1y, d1z, d2x, d2y, d2z, d3x, d3y, d3z, r
    integer :: i
    do i = 1, nb
      d1x = x(i,2,1) - x(i,1,1); d1y = x(i,2,2) - x(i,1,2); d1z = x(i,2,3) - x(i,1,3)
      d2x = x(i,3,1) - x(i,1,1); d2y = x(i,3,2) - x(i,1,2); d2z = x(i,3,3) - x(i,1,3)
      d3x = x(i,4,1) - x(i,1,1); d3y = x(i,4,2) - x(i,1,2); d3z = x(i,4,3) - x(i,1,3)
      r = p(i)/6.0_rk
      f(i,2,1) = r*(d2y*d3z - d2z*d3y); f(i,2,2) = r*(d2z*d3x - d2x*d3z); f(i,2,3) = r*(d2x*d3y - d2y*d3x)
      f(i,3,1) = r*(d3y*d1z - d3z*d1y); f(i,3,2) = r*(d3z*d1x - d3x*d1z); f(i,3,3) = r*(d3x*d1y - d3y*d1x)
      f(i,4,1) = r*(d1y*d2z - d1z*d2y); f(i,4,2) = r*(d1z*d2x - d1x*d2z); f(i,4,3) = r*(d1x*d2y - d1y*d2x)
      f(i,1,1) = -(f(i,2,1) + f(i,3,1) + f(i,4,1))
      f(i,1,2) = -(f(i,2,2) + f(i,3,2) + f(i,4,2))
      f(i,1,3) = -(f(i,2,3) + f(i,3,3) + f(i,4,3))
    end do
  end subroutine

  !> An upper bound of the largest eigenvalue of the element's isotropic
  !> elastic stiffness (bulk modulus k(i), shear modulus g), for the nodal
  !> time step (theory.md section 9). With S = sum_a grad N_a grad N_a^T,
  !> L = sum_a u_a grad N_a^T and D = |u|^2 at the least-norm u for L:
  !>   u.K u = V (lambda (tr L)^2 + 2 g |sym L|^2),  lambda = k - 2g/3,
  !>   (tr L)^2 <= tr S D,  |sym L|^2 <= |L|^2 <= s_max D,
  !> so (lambda >= 0) lambda_max <= V (lambda tr S + 2 g s_max), exact for a
  !> regular tetrahedron, with s_max <= tr S/3 + sqrt(2/3) |dev S|. The
  !> volumetric term is scaled by phi: 1 is the plain element's bound, the
  !> nodal-averaged elements take less (hydro step_volumetric_share).
  pure subroutine tet_stiffness_bound(ld, nb, vol, grad, k, g, phi, lam, g_el)
    integer, intent(in) :: ld, nb
    real(rk), intent(in) :: vol(nb), grad(ld,4,3), k(nb), g, phi
    real(rk), intent(inout) :: lam(nb)
    !> each element's shear modulus, where it depends on the state (then g is not used)
    real(rk), intent(in), optional :: g_el(nb)
    real(rk) :: sxx, syy, szz, sxy, syz, szx, tr3, dev2
    integer :: i
    ! two loops on purpose: the constant-G one is the code every constant-G
    ! deck was measured and baselined with (G as an array changed its last
    ! bits by code generation: design.md D13); the per-element one serves
    ! state-dependent shear moduli only
    if (present(g_el)) then
      do i = 1, nb
        sxx = grad(i,1,1)**2 + grad(i,2,1)**2 + grad(i,3,1)**2 + grad(i,4,1)**2
        syy = grad(i,1,2)**2 + grad(i,2,2)**2 + grad(i,3,2)**2 + grad(i,4,2)**2
        szz = grad(i,1,3)**2 + grad(i,2,3)**2 + grad(i,3,3)**2 + grad(i,4,3)**2
        sxy = grad(i,1,1)*grad(i,1,2) + grad(i,2,1)*grad(i,2,2) + grad(i,3,1)*grad(i,3,2) + grad(i,4,1)*grad(i,4,2)
        syz = grad(i,1,2)*grad(i,1,3) + grad(i,2,2)*grad(i,2,3) + grad(i,3,2)*grad(i,3,3) + grad(i,4,2)*grad(i,4,3)
        szx = grad(i,1,3)*grad(i,1,1) + grad(i,2,3)*grad(i,2,1) + grad(i,3,3)*grad(i,3,1) + grad(i,4,3)*grad(i,4,1)
        tr3 = (sxx + syy + szz)/3.0_rk
        dev2 = (sxx - tr3)**2 + (syy - tr3)**2 + (szz - tr3)**2 + 2.0_rk*(sxy**2 + syz**2 + szx**2)
        lam(i) = abs(vol(i))*(3.0_rk*phi*max(k(i) - 2.0_rk/3.0_rk*g_el(i), 0.0_rk)*tr3 &
                              + 2.0_rk*g_el(i)*(tr3 + sqrt(2.0_rk/3.0_rk*dev2)))
      end do
      return
    end if
    do i = 1, nb
      sxx = grad(i,1,1)**2 + grad(i,2,1)**2 + grad(i,3,1)**2 + grad(i,4,1)**2
      syy = grad(i,1,2)**2 + grad(i,2,2)**2 + grad(i,3,2)**2 + grad(i,4,2)**2
      szz = grad(i,1,3)**2 + grad(i,2,3)**2 + grad(i,3,3)**2 + grad(i,4,3)**2
      sxy = grad(i,1,1)*grad(i,1,2) + grad(i,2,1)*grad(i,2,2) + grad(i,3,1)*grad(i,3,2) + grad(i,4,1)*grad(i,4,2)
      syz = grad(i,1,2)*grad(i,1,3) + grad(i,2,2)*grad(i,2,3) + grad(i,3,2)*grad(i,3,3) + grad(i,4,2)*grad(i,4,3)
      szx = grad(i,1,3)*grad(i,1,1) + grad(i,2,3)*grad(i,2,1) + grad(i,3,3)*grad(i,3,1) + grad(i,4,3)*grad(i,4,1)
      tr3 = (sxx + syy + szz)/3.0_rk
      dev2 = (sxx - tr3)**2 + (syy - tr3)**2 + (szz - tr3)**2 + 2.0_rk*(sxy**2 + syz**2 + szx**2)
      lam(i) = abs(vol(i))*(3.0_rk*phi*max(k(i) - 2.0_rk/3.0_rk*g, 0.0_rk)*tr3 &
                            + 2.0_rk*g*(tr3 + sqrt(2.0_rk/3.0_rk*dev2)))
    end do
  end subroutine
end module udar_tet4
