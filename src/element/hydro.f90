!> Volumetric half of the element update, block-wise and pure: linear plus
!> quadratic artificial viscosity, the energy equation solved exactly with
!> the EOS (both EOS are linear in e), and the stable time step.
module udar_hydro
  use udar_kinds, only: rk, block_size
  use udar_config, only: material_cfg_t, eos_mie_gruneisen, strength_none
  use udar_eos, only: eos_linear_ab, eos_linear_c2, eos_mie_gruneisen_ab, eos_mie_gruneisen_c2
  implicit none
  private
  real(rk), parameter :: near_one = 0.1_rk   !< |r - 1| up to which near_one_power replaces r**beta
  !> volume strain per sound transit (-trd h/c) below which a rate counts as rounding noise, not compression
  real(rk), parameter :: compression_noise = 1.0e-12_rk
  public :: volumetric_update, dilatational_speed2, blended_volume_ratio, blended_volume_ratios, blended_pressures, &
            step_shear_modulus, step_volumetric_share, tangent_bulk_modulus

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
    real(rk) :: c2(block_size), a(block_size), b(block_size), rho, c, eq, dv, e_star, g43
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
    do i = 1, nb
      rho = mass(i)/vol(i)
      c = sqrt(c2(i))
      ! compressing faster than rounding noise (a volume strain of 1e-12 per
      ! sound transit): the sign of noise would switch the linear term's
      ! stiffening of the step on and off (visc) on a body at rest or in
      ! rigid motion, and with it the step, by the numbering
      if (trd(i)*h(i) < -compression_noise*c) then
        q(i) = rho*h(i)*(q_quad*h(i)*trd(i)**2 - q_lin*c*trd(i))
        eq = q_lin*c - q_quad*h(i)*trd(i)
      else
        q(i) = 0.0_rk
        eq = 0.0_rk
      end if
      dv = (j_new(i) - j_old(i))/mat%rho0
      e_star = e(i) + (w_dev(i) - q(i)*trd(i)*dt)*vol(i)/mass(i) - 0.5_rk*p(i)*dv
      e(i) = (e_star - 0.5_rk*dv*a(i))/(1.0_rk + 0.5_rk*dv*b(i))
      p(i) = a(i) + b(i)*e(i)
      if (no_tension(i) .and. p(i) < 0.0_rk) then
        e(i) = e_star
        p(i) = 0.0_rk
      end if
      bulk_tan(i) = tangent_bulk_modulus(c2(i), rho, g43)
      visc(i) = ((eq + sqrt(eq*eq + c2(i)))/c)**2
    end do
  end subroutine

  !> Stabilised nodal-averaged tetrahedron (doc/theory.md section 8): the
  !> volume ratio the EOS sees blends the nodal average jbar with the
  !> element's own je, geometric  J = jbar^(1-beta) je^beta  or linear
  !> J = (1-beta) jbar + beta je.
  elemental real(rk) function blended_volume_ratio(geometric, beta, jbar, je) result(j)
    logical, intent(in) :: geometric
    real(rk), intent(in) :: beta, jbar, je
    real(rk) :: r
    if (geometric) then
      r = je/jbar
      if (abs(r - 1.0_rk) <= near_one) then
        j = jbar*near_one_power(r, beta)
      else
        j = jbar*r**beta
      end if
    else
      j = (1.0_rk - beta)*jbar + beta*je
    end if
  end function

  !> blended_volume_ratio of the first nb elements of a block, the same
  !> values; the power near 1 (every element but a badly distorted one) in a
  !> loop that vectorizes.
  pure subroutine blended_volume_ratios(geometric, beta, nb, jbar, je, j)
    logical, intent(in) :: geometric
    integer, intent(in) :: nb
    real(rk), intent(in) :: beta, jbar(nb), je(nb)
    real(rk), intent(inout) :: j(nb)
    real(rk) :: r
    integer :: i
    if (.not. geometric) then
      j = (1.0_rk - beta)*jbar + beta*je
      return
    end if
    do i = 1, nb
      r = je(i)/jbar(i)
      j(i) = jbar(i)*near_one_power(min(max(r, 1.0_rk - near_one), 1.0_rk + near_one), beta)
    end do
    ! scalar: a vectorized power (libmvec) could differ from the scalar one
    ! in the last bit, by the element's place in its block
!GCC$ novector
    do i = 1, nb
      r = je(i)/jbar(i)
      if (abs(r - 1.0_rk) > near_one) j(i) = jbar(i)*r**beta
    end do
  end subroutine

  !> r^beta for |r - 1| <= near_one and 0 <= beta <= 1 as exp(beta ln r),
  !> both from series with no library call: ln r = 2 atanh(u), u = (r-1)/(r+1),
  !> |u| < 0.053, to u^13 (truncation below 1e-19); exp(y), |y| < 0.106, to
  !> y^10 (below 1e-18). Within a few ulp of r**beta.
  elemental real(rk) function near_one_power(r, beta) result(rp)
    real(rk), intent(in) :: r, beta
    real(rk) :: u, u2, y
    u = (r - 1.0_rk)/(r + 1.0_rk)
    u2 = u*u
    y = beta*2.0_rk*u*(1.0_rk + u2*(1.0_rk/3 + u2*(1.0_rk/5 + u2*(1.0_rk/7 + u2*(1.0_rk/9 + u2*(1.0_rk/11 &
        + u2*(1.0_rk/13)))))))
    rp = 1.0_rk + y*(1.0_rk + y*(1.0_rk/2 + y*(1.0_rk/6 + y*(1.0_rk/24 + y*(1.0_rk/120 + y*(1.0_rk/720 &
         + y*(1.0_rk/5040 + y*(1.0_rk/40320 + y*(1.0_rk/362880 + y*(1.0_rk/3628800))))))))))
  end function

  !> The work-conjugate split of the EOS pressure p at the blended J: the
  !> pressure the element puts into the nodal average (conjugate to jbar)
  !> and the one it applies itself (conjugate to its own je):
  !>   geometric  p_avg = (1-beta) p J/jbar,  p_own = beta p J/je
  !>   linear     p_avg = (1-beta) p,         p_own = beta p.
  elemental real(rk) function blended_pressures(geometric, own, beta, p, j, jbar, je) result(pp)
    logical, intent(in) :: geometric, own
    real(rk), intent(in) :: beta, p, j, jbar, je
    if (own) then
      pp = beta*p
      if (geometric) pp = pp*j/je
    else
      pp = (1.0_rk - beta)*p
      if (geometric) pp = pp*j/jbar
    end if
  end function

  !> The volumetric share phi of the element stiffness bound
  !> (tet_stiffness_bound): 1 for the plain element; beta + (1 - beta)
  !> patch_share for the nodal-averaged ones (beta = 0: 'nodal').
  pure real(rk) function step_volumetric_share(averaged, beta) result(phi)
    logical, intent(in) :: averaged
    real(rk), intent(in) :: beta
    phi = 1.0_rk
    if (averaged) phi = beta + (1.0_rk - beta)*patch_share
  end function

  !> The shear modulus of the wave speed and of the time step: none for
  !> materials without strength.
  pure real(rk) function step_shear_modulus(mat) result(g)
    type(material_cfg_t), intent(in) :: mat
    g = 0.0_rk
    if (mat%strength /= strength_none) g = mat%shear_modulus
  end function

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
      do i = 1, nb
        c2(i) = eos_mie_gruneisen_c2(mat%rho0, mat%c0, mat%s, mat%gamma0, j(i), p(i))
      end do
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
