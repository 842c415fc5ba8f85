!> Volumetric half of the element update, block-wise and pure: linear plus
!> quadratic artificial viscosity, the energy equation solved exactly with
!> the EOS (both EOS are linear in e), and the stable time step.
module udar_hydro
  use udar_kinds, only: rk, block_size
  use udar_config, only: material_cfg_t, eos_mie_gruneisen, strength_none, shear_constant
  use udar_flow_models, only: shear_modulus_at
  use udar_eos, only: eos_linear_ab, eos_linear_c2, eos_mie_gruneisen_ab, eos_mie_gruneisen_c2_block
  implicit none
  private
  real(rk), parameter :: near_one = 0.1_rk   !< |je/jbar - 1| up to which the blend needs no log or exp
  !> volume strain per sound transit (-trd h/c) below which a rate counts as rounding noise, not compression
  real(rk), parameter :: compression_noise = 1.0e-12_rk
  public :: volumetric_update, dilatational_speed2, blended_volume_ratio, blended_volume_ratios, blended_pressures, &
            blend_exponent, &
            step_shear_modulus, element_shear_moduli, step_volumetric_share, tangent_bulk_modulus, &
            shock_heated_temperature

  !> The share of an element's volumetric stiffness that the nodal time step
  !> of the nodal-averaged elements counts beyond their own beta: their
  !> averaged part acts over the nodal patch. Measured (theory.md section 9):
  !> with it the assembled limit is still at least 1.41 times the nodal step
  !> on every mesh tried, the plain element's exact bound at least 1.22.
  real(rk), parameter :: patch_share = 1.0_rk/6.0_rk

contains

  !> For the first nb elements of a block: viscosity q from the rate of
  !> volume change trd = tr D (compression only), then
  !>   e(n+1) = e(n) + (w_dev - q trd dt) V/m - (p(n) + p(n+1)) dv / 2,
  !>   dv = (J(n+1) - J(n)) / rho0,  p(n+1) = A(J(n+1)) + B e(n+1),
  !> solved for e(n+1) in closed form. For the time step (theory.md
  !> section 9): the tangent bulk modulus rho c_b^2 and the factor by which
  !> the viscosity shortens the element's step, squared, as a stiffness
  !> factor: ((Q + sqrt(Q^2 + c^2))/c)^2, Q = q_lin c + q_quad h |trd|
  !> (the element step h/(Q + sqrt(Q^2 + c^2)) of Hallquist, LS-DYNA theory
  !> manual, section 18, over h/c).
  !> Fractured elements (no_tension) carry no tension: where the EOS would
  !> give p < 0 the pressure is 0 and the energy equation has no p dv term
  !> for the new pressure.
  pure subroutine volumetric_update(mat, q_lin, q_quad, nb, dt, vol, h, trd, mass, j_old, j_new, &
                                    w_dev, no_tension, e, p, q, bulk_tan, visc)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: q_lin, q_quad, dt
    integer, intent(in) :: nb
    real(rk), intent(in) :: vol(nb), h(nb), trd(nb), mass(nb), j_old(nb), j_new(nb), w_dev(nb)
    logical, intent(in) :: no_tension(nb)
    real(rk), intent(inout) :: e(nb), p(nb), q(nb)
    real(rk), intent(out) :: bulk_tan(nb), visc(nb)
    real(rk) :: c2(block_size), a(block_size), b(block_size), rho, c, eq, dv, e_star, e_new, p_new, q_c, eq_c, g43
    logical :: compressing, clipped
    integer :: i
    call dilatational_speed2(mat, nb, j_old, p, mass, vol, c2)
    g43 = 4.0_rk/3.0_rk*step_shear_modulus(mat)
    if (mat%eos == eos_mie_gruneisen) then
      do i = 1, nb
        call eos_mie_gruneisen_ab(mat%rho0, mat%c0, mat%s, mat%gamma0, j_new(i), a(i), b(i))
      end do
    else
      do i = 1, nb
        call eos_linear_ab(mat%bulk_modulus, j_new(i), a(i), b(i))
      end do
    end if
    ! both sides of each choice computed, then merged: so the loop vectorizes
    do i = 1, nb
      rho = mass(i)/vol(i)
      c = sqrt(c2(i))
      ! compressing faster than rounding noise (a volume strain of 1e-12 per
      ! sound transit): the sign of noise would switch the linear term's
      ! stiffening of the step on and off (visc) on a body at rest or in
      ! rigid motion, and with it the step, by the numbering
      compressing = trd(i)*h(i) < -compression_noise*c
      q_c = rho*h(i)*(q_quad*h(i)*trd(i)**2 - q_lin*c*trd(i))
      eq_c = q_lin*c - q_quad*h(i)*trd(i)
      q(i) = merge(q_c, 0.0_rk, compressing)
      eq = merge(eq_c, 0.0_rk, compressing)
      dv = (j_new(i) - j_old(i))/mat%rho0
      e_star = e(i) + (w_dev(i) - q(i)*trd(i)*dt)*vol(i)/mass(i) - 0.5_rk*p(i)*dv
      e_new = (e_star - 0.5_rk*dv*a(i))/(1.0_rk + 0.5_rk*dv*b(i))
      p_new = a(i) + b(i)*e_new
      clipped = no_tension(i) .and. p_new < 0.0_rk
      e(i) = merge(e_star, e_new, clipped)
      p(i) = merge(0.0_rk, p_new, clipped)
      bulk_tan(i) = tangent_bulk_modulus(c2(i), rho, g43)
      visc(i) = ((eq + sqrt(eq*eq + c2(i)))/c)**2
    end do
  end subroutine

  !> The temperature after a step of volume change from j_old to j_new
  !> (V/V0) with viscous work q_work (J/kg, >= 0 in compression) at specific
  !> heat c_v, Grueneisen gamma0 (Gamma rho = gamma0 rho0, as the
  !> Mie-Grueneisen EOS): c_v dT = dq - Gamma c_v T dv/v integrates, over
  !> the volume change, to T exp(-gamma0 (j_new - j_old)), exact on an
  !> isentrope; the viscosity's work is the shock's entropy
  !> (doc/theory.md section 16).
  pure elemental real(rk) function shock_heated_temperature(gamma0, c_v, t, j_old, j_new, q_work) result(t_new)
    real(rk), intent(in) :: gamma0, c_v, t, j_old, j_new, q_work
    t_new = t*exp(-gamma0*(j_new - j_old)) + q_work/c_v
  end function

  !> Stabilised nodal-averaged tetrahedron (doc/theory.md section 8.1): the
  !> volume ratio j the EOS sees blends the nodal average jbar with the
  !> element's own je, geometric  j = jbar exp(phi(s)), s = ln(je/jbar), or
  !> linear  j = (1-beta0) jbar + beta0 je; share is the weight of the
  !> element's own ratio, phi'(s) (blend_exponent) or beta0.
  elemental subroutine blended_volume_ratio(geometric, beta0, beta1, s1, jbar, je, j, share)
    logical, intent(in) :: geometric
    real(rk), intent(in) :: beta0, beta1, s1, jbar, je
    real(rk), intent(out) :: j, share
    real(rk) :: r, phi
    r = je/jbar
    if (.not. geometric) then
      j = (1.0_rk - beta0)*jbar + beta0*je
      share = beta0
    else if (abs(r - 1.0_rk) <= near_one) then
      call blend_exponent(beta0, beta1, s1, near_one_log(r), phi, share)
      j = jbar*near_zero_exp(phi)
    else
      call blend_exponent(beta0, beta1, s1, log(r), phi, share)
      j = jbar*exp(phi)
    end if
  end subroutine

  !> blended_volume_ratio of the first nb elements of a block, the same
  !> values; near jbar (every element but a badly distorted one) in a loop
  !> that vectorizes.
  pure subroutine blended_volume_ratios(geometric, beta0, beta1, s1, nb, jbar, je, j, share)
    logical, intent(in) :: geometric
    integer, intent(in) :: nb
    real(rk), intent(in) :: beta0, beta1, s1, jbar(nb), je(nb)
    real(rk), intent(inout) :: j(nb), share(nb)
    real(rk) :: r, phi
    integer :: i
    if (.not. geometric) then
      j = (1.0_rk - beta0)*jbar + beta0*je
      share = beta0
      return
    end if
    do i = 1, nb
      r = min(max(je(i)/jbar(i), 1.0_rk - near_one), 1.0_rk + near_one)
      call blend_exponent(beta0, beta1, s1, near_one_log(r), phi, share(i))
      j(i) = jbar(i)*near_zero_exp(phi)
    end do
    ! scalar: a vectorized log or exp (libmvec) could differ from the scalar
    ! one in the last bit, by the element's place in its block
!GCC$ novector
    do i = 1, nb
      r = je(i)/jbar(i)
      if (abs(r - 1.0_rk) > near_one) then
        call blend_exponent(beta0, beta1, s1, log(r), phi, share(i))
        j(i) = jbar(i)*exp(phi)
      end if
    end do
  end subroutine

  !> The exponent of the geometric blend and its slope, odd in s: the slope
  !> (the element's own share) is beta0 at s = 0 and rises as (s/s1)^2 to
  !> beta1 at |s| = s1, beta1 beyond; phi is its integral, so phi and phi'
  !> are continuous. beta1 = beta0: phi = beta0 s, 0.5.2's constant share.
  !> Written with a = min(|s|, s1) and no condition, so that the block loop
  !> vectorizes (gfortran 12 will not if-convert a select here).
  elemental subroutine blend_exponent(beta0, beta1, s1, s, phi, slope)
    real(rk), intent(in) :: beta0, beta1, s1, s
    real(rk), intent(out) :: phi, slope
    real(rk) :: a, x
    a = min(abs(s), s1)
    x = a/s1
    slope = beta0 + (beta1 - beta0)*x*x
    phi = beta0*s + (beta1 - beta0)*sign(a*x*x/3.0_rk + (abs(s) - a), s)
  end subroutine

  !> ln r for |r - 1| <= near_one from the series of 2 atanh(u),
  !> u = (r-1)/(r+1), |u| < 0.053, to u^13 (truncation below 1e-19): no
  !> library call, so the loop vectorizes. Within a few ulp of log(r).
  elemental real(rk) function near_one_log(r) result(s)
    real(rk), intent(in) :: r
    real(rk) :: u, u2
    u = (r - 1.0_rk)/(r + 1.0_rk)
    u2 = u*u
    s = 2.0_rk*u*(1.0_rk + u2*(1.0_rk/3 + u2*(1.0_rk/5 + u2*(1.0_rk/7 + u2*(1.0_rk/9 + u2*(1.0_rk/11 &
        + u2*(1.0_rk/13)))))))
  end function

  !> exp(y) for |y| <= 0.106 (the blend's exponent near jbar: |s| <= 0.106,
  !> slope at most 1) from its series to y^10 (truncation below 1e-18).
  elemental real(rk) function near_zero_exp(y) result(ey)
    real(rk), intent(in) :: y
    ey = 1.0_rk + y*(1.0_rk + y*(1.0_rk/2 + y*(1.0_rk/6 + y*(1.0_rk/24 + y*(1.0_rk/120 + y*(1.0_rk/720 &
         + y*(1.0_rk/5040 + y*(1.0_rk/40320 + y*(1.0_rk/362880 + y*(1.0_rk/3628800))))))))))
  end function

  !> The work-conjugate split of the EOS pressure p at the blended J: the
  !> pressure the element puts into the nodal average (conjugate to jbar)
  !> and the one it applies itself (conjugate to its own je):
  !>   geometric  p_avg = (1-share) p J/jbar,  p_own = share p J/je
  !>   linear     p_avg = (1-share) p,         p_own = share p
  !> with share from blended_volume_ratio (dJ/dje = share J/je).
  elemental real(rk) function blended_pressures(geometric, own, share, p, j, jbar, je) result(pp)
    logical, intent(in) :: geometric, own
    real(rk), intent(in) :: share, p, j, jbar, je
    if (own) then
      pp = share*p
      if (geometric) pp = pp*j/je
    else
      pp = (1.0_rk - share)*p
      if (geometric) pp = pp*j/jbar
    end if
  end function

  !> The volumetric share phi of the element stiffness bound
  !> (tet_stiffness_bound, tri_stiffness_bound): 1 for the plain element;
  !> beta + (1 - beta) patch for the nodal-averaged ones (beta = 0: 'nodal'),
  !> patch the element kind's share (patch_share for tetrahedra,
  !> tri_patch_share for triangles).
  pure real(rk) function step_volumetric_share(averaged, beta, patch) result(phi)
    logical, intent(in) :: averaged
    real(rk), intent(in) :: beta
    real(rk), intent(in), optional :: patch   !< the element kind's patch share (default the tetrahedron's)
    phi = 1.0_rk
    if (.not. averaged) return
    if (present(patch)) then
      phi = beta + (1.0_rk - beta)*patch
    else
      phi = beta + (1.0_rk - beta)*patch_share
    end if
  end function

  !> The shear modulus of the wave speed and of the time step: none for
  !> materials without strength.
  pure real(rk) function step_shear_modulus(mat) result(g)
    type(material_cfg_t), intent(in) :: mat
    g = 0.0_rk
    if (mat%strength /= strength_none) g = mat%shear_modulus
  end function

  !> The shear moduli g(1:nb) of the elements' stiffness bounds:
  !> step_shear_modulus, or where it depends on the state (shear_model) each
  !> element's at pressure p (Pa), temperature temp (K) and volume ratio j
  !> (each its own: a block's largest made the step depend on which elements
  !> share a block, and so on the rank count).
  pure subroutine element_shear_moduli(mat, nb, p, temp, j, g)
    type(material_cfg_t), intent(in) :: mat
    integer, intent(in) :: nb
    real(rk), intent(in) :: p(nb), temp(nb), j(nb)
    real(rk), intent(out) :: g(nb)
    integer :: i
    if (mat%shear_model == shear_constant .or. mat%strength == strength_none) then
      g = step_shear_modulus(mat)
    else
      do i = 1, nb
        g(i) = shear_modulus_at(mat, p(i), temp(i), 1.0_rk/j(i))
      end do
    end if
  end subroutine

  !> The tangent bulk modulus rho c_b^2 of the stiffness bound from the
  !> squared dilatational speed c2 = c_b^2 + g43/rho (dilatational_speed2),
  !> g43 = 4/3 of step_shear_modulus.
  elemental real(rk) function tangent_bulk_modulus(c2, rho, g43) result(k)
    real(rk), intent(in) :: c2, rho, g43
    k = rho*c2 - g43
  end function

  !> Square of the dilatational wave speed: bulk sound speed at (J, p) plus
  !> 4G/(3 rho) for materials with strength.
  pure subroutine dilatational_speed2(mat, nb, j, p, mass, vol, c2)
    type(material_cfg_t), intent(in) :: mat
    integer, intent(in) :: nb
    real(rk), intent(in) :: j(nb), p(nb), mass(nb), vol(nb)
    real(rk), intent(inout) :: c2(nb)
    real(rk) :: g43
    integer :: i
    if (mat%eos == eos_mie_gruneisen) then
      call eos_mie_gruneisen_c2_block(mat%rho0, mat%c0, mat%s, mat%gamma0, nb, j, p, c2)
    else
      do i = 1, nb
        c2(i) = eos_linear_c2(mat%bulk_modulus, mat%rho0)
      end do
    end if
    g43 = 4.0_rk/3.0_rk*step_shear_modulus(mat)
    do i = 1, nb
      c2(i) = c2(i) + g43*vol(i)/mass(i)
    end do
  end subroutine
end module udar_hydro
