!> Deviatoric stress update: Jaumann rotation (Hughes-Winget / Cayley form,
!> exactly orthogonal), hypoelastic trial step and radial return to the von
!> Mises surface. Pure, block-wise (element index innermost).
module udar_strength
  use udar_kinds, only: rk
  use udar_config, only: material_cfg_t, strength_none, strength_elastic, &
      strength_perfectly_plastic, strength_linear_hardening, strength_johnson_cook
  implicit none
  private
  public :: strength_block, yield_stress, von_mises, thermal_softening, initial_hardening

contains

  pure real(rk) function von_mises(s) result(q)
    real(rk), intent(in) :: s(6)
    q = sqrt(1.5_rk*(s(1)**2 + s(2)**2 + s(3)**2 + 2.0_rk*(s(4)**2 + s(5)**2 + s(6)**2)))
  end function

  !> Flow stress of the material at plastic strain eps_p, equivalent strain
  !> rate rate (1/s) and temperature temp (K).
  pure real(rk) function yield_stress(mat, eps_p, rate, temp) result(sy)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: eps_p, rate, temp
    select case (mat%strength)
    case (strength_perfectly_plastic)
      sy = mat%yield_stress
    case (strength_linear_hardening)
      sy = mat%yield_stress + mat%hardening_modulus*eps_p
    case (strength_johnson_cook)
      sy = jc_hardening(mat, eps_p)*jc_rate_factor(mat, rate)*jc_thermal_factor(mat, temp)
    case default
      sy = huge(1.0_rk)
    end select
  end function

  !> Deviatoric stress update of the first nb elements of a block over dt:
  !> Jaumann rotation s <- R s R^T with R = (I - dt W/2)^-1 (I + dt W/2)
  !> (Hughes and Winget 1980: exactly orthogonal), hypoelastic trial step
  !> s += 2 G dt dev(D), radial return to the von Mises surface. d is the
  !> strain rate (xx,yy,zz,xy,yz,zx), w the spin (W_xy, W_yz, W_zx).
  !> Returns the deviatoric and plastic work per unit volume (J/m3).
  !> The flow stress is hard * soft * (rate factor): hard = strain hardening
  !> (state, updated here), soft = thermal softening (state, from the
  !> temperature at the step's start). Johnson-Cook uses the step's
  !> equivalent deviatoric (total) strain rate; both are fixed in the return.
  pure subroutine strength_block(mat, ld, nb, dt, d, w, soft, hard, s, eps_p, w_dev, w_plastic)
    type(material_cfg_t), intent(in) :: mat
    integer, intent(in) :: ld, nb
    real(rk), intent(in) :: dt, d(ld,6), w(ld,3), soft(ld)
    real(rk), intent(inout) :: hard(ld), s(ld,6), eps_p(ld)
    real(rk), intent(inout) :: w_dev(ld), w_plastic(ld)
    real(rk) :: q_trial(ld), rate(ld), rot_work(ld), trial_work(ld), scale(ld), d_eps(ld), sy(ld)
    real(rk) :: a, b, cc, c, r11, r12, r13, r21, r22, r23, r31, r32, r33
    real(rk) :: t11, t12, t13, t21, t22, t23, t31, t32, t33, x(6), dd(6), tr3, g2dt, factor
    integer :: i
    if (mat%strength == strength_none) then
      s(1:nb,:) = 0.0_rk; w_dev(1:nb) = 0.0_rk; w_plastic(1:nb) = 0.0_rk
      return
    end if
    g2dt = 2.0_rk*mat%shear_modulus*dt
    do i = 1, nb
      a = 0.5_rk*dt*w(i,1); b = 0.5_rk*dt*w(i,2); cc = 0.5_rk*dt*w(i,3)
      c = 2.0_rk/(1.0_rk + a*a + b*b + cc*cc)
      ! R = I + c (Omega + Omega^2), Omega_12 = a, Omega_23 = b, Omega_31 = cc
      r11 = 1.0_rk - c*(a*a + cc*cc); r22 = 1.0_rk - c*(a*a + b*b); r33 = 1.0_rk - c*(b*b + cc*cc)
      r12 = c*(a + b*cc);  r21 = c*(-a + b*cc)
      r23 = c*(b + a*cc);  r32 = c*(-b + a*cc)
      r13 = c*(-cc + a*b); r31 = c*(cc + a*b)
      ! T = R s, then x = T R^T
      t11 = r11*s(i,1) + r12*s(i,4) + r13*s(i,6)
      t12 = r11*s(i,4) + r12*s(i,2) + r13*s(i,5)
      t13 = r11*s(i,6) + r12*s(i,5) + r13*s(i,3)
      t21 = r21*s(i,1) + r22*s(i,4) + r23*s(i,6)
      t22 = r21*s(i,4) + r22*s(i,2) + r23*s(i,5)
      t23 = r21*s(i,6) + r22*s(i,5) + r23*s(i,3)
      t31 = r31*s(i,1) + r32*s(i,4) + r33*s(i,6)
      t32 = r31*s(i,4) + r32*s(i,2) + r33*s(i,5)
      t33 = r31*s(i,6) + r32*s(i,5) + r33*s(i,3)
      x(1) = t11*r11 + t12*r12 + t13*r13
      x(2) = t21*r21 + t22*r22 + t23*r23
      x(3) = t31*r31 + t32*r32 + t33*r33
      x(4) = t11*r21 + t12*r22 + t13*r23
      x(5) = t21*r31 + t22*r32 + t23*r33
      x(6) = t31*r11 + t32*r12 + t33*r13
      tr3 = (d(i,1) + d(i,2) + d(i,3))/3.0_rk
      dd(1) = d(i,1) - tr3; dd(2) = d(i,2) - tr3; dd(3) = d(i,3) - tr3
      dd(4) = d(i,4); dd(5) = d(i,5); dd(6) = d(i,6)
      rot_work(i) = dot6(x, dd)
      x = x + g2dt*dd
      trial_work(i) = dot6(x, dd)
      s(i,1) = x(1); s(i,2) = x(2); s(i,3) = x(3); s(i,4) = x(4); s(i,5) = x(5); s(i,6) = x(6)
      q_trial(i) = sqrt(1.5_rk*(x(1)**2 + x(2)**2 + x(3)**2 + 2.0_rk*(x(4)**2 + x(5)**2 + x(6)**2)))
      rate(i) = sqrt(2.0_rk/3.0_rk*(dd(1)**2 + dd(2)**2 + dd(3)**2 + 2.0_rk*(dd(4)**2 + dd(5)**2 + dd(6)**2)))
    end do
    select case (mat%strength)
    case (strength_perfectly_plastic, strength_linear_hardening)
      do i = 1, nb
        sy(i) = hard(i)
        d_eps(i) = max(q_trial(i) - sy(i), 0.0_rk)/(3.0_rk*mat%shear_modulus + mat%hardening_modulus)
        sy(i) = sy(i) + mat%hardening_modulus*d_eps(i)
        hard(i) = sy(i)
      end do
    case (strength_johnson_cook)
      do i = 1, nb
        d_eps(i) = 0.0_rk
        factor = jc_rate_factor(mat, rate(i))*soft(i)
        sy(i) = factor*hard(i)
        if (q_trial(i) > sy(i)) then
          call jc_return(mat, q_trial(i), eps_p(i), factor, d_eps(i), sy(i))
          if (factor > 0.0_rk) hard(i) = sy(i)/factor
        end if
      end do
    case default
      d_eps(1:nb) = 0.0_rk
    end select
    do i = 1, nb
      scale(i) = 1.0_rk
      w_plastic(i) = 0.0_rk
      if (d_eps(i) > 0.0_rk) then
        scale(i) = sy(i)/q_trial(i)
        w_plastic(i) = sy(i)*d_eps(i)
      end if
      s(i,1) = scale(i)*s(i,1); s(i,2) = scale(i)*s(i,2); s(i,3) = scale(i)*s(i,3)
      s(i,4) = scale(i)*s(i,4); s(i,5) = scale(i)*s(i,5); s(i,6) = scale(i)*s(i,6)
      eps_p(i) = eps_p(i) + d_eps(i)
      w_dev(i) = 0.5_rk*dt*(rot_work(i) + scale(i)*trial_work(i))
    end do
  end subroutine

  !> Thermal softening factor of the flow stress at temperature temp (1
  !> for models without temperature dependence).
  pure elemental real(rk) function thermal_softening(mat, temp)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: temp
    thermal_softening = 1.0_rk
    if (mat%strength == strength_johnson_cook) thermal_softening = jc_thermal_factor(mat, temp)
  end function

  !> Strain-hardening part of the flow stress of virgin material.
  pure elemental real(rk) function initial_hardening(mat)
    type(material_cfg_t), intent(in) :: mat
    select case (mat%strength)
    case (strength_perfectly_plastic, strength_linear_hardening)
      initial_hardening = mat%yield_stress
    case (strength_johnson_cook)
      initial_hardening = mat%jc_a
    case default
      initial_hardening = huge(1.0_rk)
    end select
  end function

  pure real(rk) function jc_hardening(mat, eps_p)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: eps_p
    jc_hardening = mat%jc_a
    if (eps_p > 0.0_rk) jc_hardening = jc_hardening + mat%jc_b*eps_p**mat%jc_n
  end function

  pure real(rk) function jc_rate_factor(mat, rate)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: rate
    jc_rate_factor = 1.0_rk
    if (rate > mat%jc_rate0) jc_rate_factor = 1.0_rk + mat%jc_c*log(rate/mat%jc_rate0)
  end function

  pure elemental real(rk) function jc_thermal_factor(mat, temp)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: temp
    real(rk) :: tstar
    tstar = (temp - mat%t_room)/(mat%t_melt - mat%t_room)
    if (tstar >= 1.0_rk) then
      jc_thermal_factor = 0.0_rk
    else if (tstar > 0.0_rk) then
      jc_thermal_factor = 1.0_rk - tstar**mat%jc_m
    else
      jc_thermal_factor = 1.0_rk
    end if
  end function

  !> Solves q_trial - 3 G de = factor (A + B (eps_p + de)^n) for de > 0 by
  !> Newton's method kept inside a shrinking bracket (the power law has an
  !> infinite slope at zero plastic strain), started from the return with
  !> the hardening slope of the current state: usually 2-3 iterations, one
  !> power each. sy enters with the flow stress at eps_p and leaves with the
  !> one at eps_p + de.
  pure subroutine jc_return(mat, q_trial, eps_p, factor, de, sy)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: q_trial, eps_p, factor
    real(rk), intent(inout) :: de, sy
    real(rk) :: g3, lo, hi, f, fp, e, pw, de_new, slope
    integer :: it
    g3 = 3.0_rk*mat%shear_modulus
    lo = 0.0_rk
    hi = (q_trial - factor*mat%jc_a)/g3     ! the return with no hardening at all
    slope = 0.0_rk
    if (eps_p > 0.0_rk) slope = mat%jc_n*(sy - factor*mat%jc_a)/eps_p
    if (factor <= 0.0_rk) then   ! melted: no strength left
      de = q_trial/g3; sy = 0.0_rk
      return
    end if
    de = min((q_trial - sy)/(g3 + slope), hi)
    do it = 1, 60
      e = eps_p + de
      pw = 0.0_rk
      if (e > 0.0_rk) pw = e**mat%jc_n
      f = q_trial - g3*de - factor*(mat%jc_a + mat%jc_b*pw)
      if (f > 0.0_rk) then
        lo = de
      else
        hi = de
      end if
      fp = -g3 - factor*mat%jc_b*mat%jc_n*pw/max(e, tiny(1.0_rk))
      de_new = de - f/fp
      if (de_new <= lo .or. de_new >= hi) de_new = 0.5_rk*(lo + hi)
      if (abs(de_new - de) <= 1.0e-12_rk*de_new) then
        de = de_new
        exit
      end if
      de = de_new
    end do
    ! on the yield surface by construction of the return
    sy = q_trial - g3*de
  end subroutine

  pure real(rk) function dot6(a, b)
    real(rk), intent(in) :: a(6), b(6)
    dot6 = a(1)*b(1) + a(2)*b(2) + a(3)*b(3) + 2.0_rk*(a(4)*b(4) + a(5)*b(5) + a(6)*b(6))
  end function
end module udar_strength
