!> Deviatoric stress update: Jaumann rotation (Hughes-Winget / Cayley form,
!> exactly orthogonal), hypoelastic trial step and radial return to the von
!> Mises surface. Pure, block-wise (element index innermost).
module udar_strength
  use udar_kinds, only: rk, block_size
  use udar_config, only: material_cfg_t, strength_none, strength_elastic, &
      strength_perfectly_plastic, strength_linear_hardening, strength_johnson_cook, jc_rate_plastic, &
      strength_zerilli_armstrong, strength_steinberg_guinan, strength_mts, strength_ptw, strength_steinberg_lund, shear_constant
  use udar_flow_models, only: melt_temperature, shear_modulus_at, model_flow_stress, model_return, newton_step, &
      mts_flow_stress, mts_return
  implicit none
  private
  public :: strength_block, yield_stress, von_mises, thermal_softening, thermal_softening_update, &
            initial_hardening, power_ratio

contains

  pure real(rk) function von_mises(s) result(q)
    real(rk), intent(in) :: s(6)
    q = sqrt(1.5_rk*(s(1)**2 + s(2)**2 + s(3)**2 + 2.0_rk*(s(4)**2 + s(5)**2 + s(6)**2)))
  end function

  !> Flow stress of the material at plastic strain eps_p, equivalent strain
  !> rate rate (1/s) and temperature temp (K); the models of
  !> udar_flow_models also at pressure p (Pa, default 0) and eta = rho/rho0
  !> (default 1); the MTS model at internal stress sigma_e = eps_p (its
  !> state variable in place of the plastic strain).
  pure real(rk) function yield_stress(mat, eps_p, rate, temp, p, eta) result(sy)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: eps_p, rate, temp
    real(rk), intent(in), optional :: p, eta
    real(rk) :: pp, et, slope
    select case (mat%strength)
    case (strength_perfectly_plastic)
      sy = mat%yield_stress
    case (strength_linear_hardening)
      sy = mat%yield_stress + mat%hardening_modulus*eps_p
    case (strength_johnson_cook)
      sy = jc_hardening(mat, eps_p)*jc_rate_factor(mat, rate)*jc_thermal_factor(mat, temp)
    case (strength_zerilli_armstrong, strength_steinberg_guinan, strength_steinberg_lund, strength_ptw)
      pp = 0.0_rk
      et = 1.0_rk
      if (present(p)) pp = p
      if (present(eta)) et = eta
      call model_flow_stress(mat, eps_p, rate, temp, melt_temperature(mat, et), &
                             shear_modulus_at(mat, pp, temp, et)/mat%shear_modulus, mat%rho0*et, sy, slope)
    case (strength_mts)
      pp = 0.0_rk
      et = 1.0_rk
      if (present(p)) pp = p
      if (present(eta)) et = eta
      sy = mts_flow_stress(mat, eps_p, rate, temp, melt_temperature(mat, et), shear_modulus_at(mat, pp, temp, et))
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
  !> The models of udar_flow_models (Zerilli-Armstrong, Steinberg-Guinan)
  !> take the temperature temp (K), pressure p (Pa) and eta = rho/rho0 of
  !> the step's start, and the same total rate; their shear modulus (trial
  !> step and return) is shear_modulus_at those, hard keeps their flow stress.
  pure subroutine strength_block(mat, ld, nb, dt, d, w, soft, temp, p, eta, hard, s, eps_p, w_dev, w_plastic)
    type(material_cfg_t), intent(in) :: mat
    integer, intent(in) :: ld, nb
    real(rk), intent(in) :: dt, d(ld,6), w(ld,3), soft(nb), temp(nb), p(nb), eta(nb)
    real(rk), intent(inout) :: hard(nb), s(ld,6), eps_p(nb)
    real(rk), intent(inout) :: w_dev(nb), w_plastic(nb)
    real(rk), dimension(block_size) :: q_trial, rate, rot_work, trial_work, scale, d_eps, sy, g2dt, g_el, rate_factor
    real(rk) :: a, b, cc, c, r11, r12, r13, r21, r22, r23, r31, r32, r33
    real(rk) :: t11, t12, t13, t21, t22, t23, t31, t32, t33, x(6), dd(6), tr3, factor, t_m, slope
    integer :: i, n_flow, flowing(block_size)
    if (mat%strength == strength_none) then
      s(1:nb,:) = 0.0_rk; w_dev(1:nb) = 0.0_rk; w_plastic(1:nb) = 0.0_rk
      return
    end if
    if (mat%shear_model == shear_constant) then
      ! the common case: no per-element modulus to evaluate
      g_el(1:nb) = mat%shear_modulus
    else
      g_el(1:nb) = shear_modulus_at(mat, p, temp, eta)
    end if
    g2dt(1:nb) = 2.0_rk*g_el(1:nb)*dt
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
      x = x + g2dt(i)*dd
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
      ! the elements that flow, listed, then returned together
      n_flow = 0
      do i = 1, nb
        d_eps(i) = 0.0_rk
        sy(i) = soft(i)*hard(i)
        rate_factor(i) = 1.0_rk
        if (q_trial(i) <= sy(i)) cycle          ! the rate factor is >= 1: elastic
        if (mat%jc_rate_form /= jc_rate_plastic) then
          rate_factor(i) = jc_rate_factor(mat, rate(i))
          sy(i) = soft(i)*rate_factor(i)*hard(i)
          if (q_trial(i) <= sy(i)) cycle
        end if
        n_flow = n_flow + 1
        flowing(n_flow) = i
      end do
      call jc_returns(mat, dt, n_flow, flowing, q_trial, eps_p, soft, rate_factor, mat%jc_rate_form == jc_rate_plastic, &
                      d_eps, sy, hard)
    case (strength_zerilli_armstrong, strength_steinberg_guinan, strength_steinberg_lund, strength_ptw)
      do i = 1, nb
        d_eps(i) = 0.0_rk
        t_m = melt_temperature(mat, eta(i))
        call model_flow_stress(mat, eps_p(i), rate(i), temp(i), t_m, g_el(i)/mat%shear_modulus, mat%rho0*eta(i), &
                               sy(i), slope)
        if (q_trial(i) <= sy(i)) cycle
        if (g_el(i) <= 0.0_rk) then
          ! no shear stiffness left: no deviator either
          s(i,:) = 0.0_rk
          cycle
        end if
        call model_return(mat, g_el(i), q_trial(i), eps_p(i), rate(i), temp(i), t_m, g_el(i)/mat%shear_modulus, &
                          mat%rho0*eta(i), d_eps(i), sy(i))
        hard(i) = sy(i)
      end do
    case (strength_mts)
      ! hard is the internal stress sigma_e
      do i = 1, nb
        d_eps(i) = 0.0_rk
        t_m = melt_temperature(mat, eta(i))
        sy(i) = mts_flow_stress(mat, hard(i), rate(i), temp(i), t_m, g_el(i))
        if (q_trial(i) <= sy(i)) cycle
        if (g_el(i) <= 0.0_rk) then
          s(i,:) = 0.0_rk
          cycle
        end if
        call mts_return(mat, g_el(i), q_trial(i), rate(i), temp(i), t_m, hard(i), d_eps(i), sy(i))
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
    case (strength_zerilli_armstrong)
      initial_hardening = mat%za_c0 + mat%za_c1
    case (strength_mts, strength_ptw)
      initial_hardening = 0.0_rk          ! sigma_e of annealed material; PTW: unused
    case (strength_steinberg_guinan, strength_steinberg_lund)
      ! Lund's rate term adds to it at the step's rate
      initial_hardening = min(mat%sg_y0*(1.0_rk + mat%sg_beta*mat%sg_eps_i)**mat%sg_n, mat%sg_ymax)
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

  !> The Johnson-Cook return: solves for de > 0
  !>   q_trial - 3 G de = soft (A + B (eps_p + de)^n) R,
  !> with R = rate_factor fixed (rate term from the total strain rate), or,
  !> when plastic_rate, R = 1 + C ln max(de/(dt rate0), 1) (Johnson and
  !> Cook's plastic strain rate: the rate term depends on the unknown). The
  !> left side decreases strictly in de and is <= 0 at the no-hardening,
  !> no-rate return, which bounds the bracket of a safeguarded Newton
  !> iteration started from the return with the current hardening slope.
  !> hard = A + B eps_p^n is the cached state, so (eps_p + de)^n =
  !> eps_p^n (1 + de/eps_p)^n needs no power for the small increments of a
  !> flowing element (power_ratio), and each later iterate's power is the
  !> last one's times (1 + step/(eps_p + de_last))^n: one power at most per
  !> return. sy enters with the flow stress at the start and leaves with
  !> the one at eps_p + de; hard is updated.
  !> The n elements listed in el (block indices) iterate side by side, one
  !> Newton step of each in turn, those that converged leaving the list:
  !> each element's arithmetic is that of its own iteration, and the
  !> independent iterations overlap in the processor (one after the other,
  !> each waited on its divisions).
  pure subroutine jc_returns(mat, dt, n, el, q_trial, eps_p, soft, rate_factor, plastic_rate, de, sy, hard)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: dt
    integer, intent(in) :: n, el(n)
    real(rk), intent(in), dimension(block_size) :: q_trial, eps_p, soft, rate_factor
    logical, intent(in) :: plastic_rate
    real(rk), intent(inout), dimension(block_size) :: de, sy, hard
    real(rk), dimension(block_size) :: lo, hi, pw, de_pw, inv_e_pw, r
    real(rk) :: g3, f, fp, e, pw0, h, slope, de_rate1, inv_e
    integer :: it, k, i, n_left, n_next, left(block_size)
    logical :: done
    g3 = 3.0_rk*mat%shear_modulus
    de_rate1 = dt*mat%jc_rate0          ! below this increment the plastic-rate factor is 1
    n_left = 0
    do k = 1, n
      i = el(k)
      r(i) = rate_factor(i)
      if (soft(i) <= 0.0_rk .or. (mat%jc_b <= 0.0_rk .and. .not. plastic_rate)) then
        ! melted, or no hardening with a fixed rate factor: closed form
        de(i) = max(q_trial(i) - sy(i), 0.0_rk)/g3
        sy(i) = q_trial(i) - g3*de(i)
        cycle
      end if
      pw0 = 0.0_rk
      if (mat%jc_b > 0.0_rk) pw0 = max(hard(i) - mat%jc_a, 0.0_rk)/mat%jc_b     ! eps_p^n
      lo(i) = 0.0_rk
      hi(i) = (q_trial(i) - soft(i)*r(i)*mat%jc_a)/g3
      slope = 0.0_rk
      ! 1/(eps_p + the increment pw belongs to): the series' argument is a
      ! product, the one division of an iteration being Newton's step
      inv_e_pw(i) = 0.0_rk
      if (eps_p(i) > 0.0_rk) then
        inv_e_pw(i) = 1.0_rk/eps_p(i)
        slope = soft(i)*r(i)*mat%jc_b*mat%jc_n*pw0*inv_e_pw(i)
      end if
      de(i) = min((q_trial(i) - sy(i))/(g3 + slope), hi(i))
      de_pw(i) = 0.0_rk
      ! the first iterate's power
      e = eps_p(i) + de(i)
      if (eps_p(i) > 0.0_rk) then
        pw(i) = pw0*power_ratio(de(i)*inv_e_pw(i), mat%jc_n)
      else
        pw(i) = e**mat%jc_n
      end if
      n_left = n_left + 1
      left(n_left) = i
    end do
    do it = 1, 80
      if (n_left == 0) exit
      n_next = 0
      do k = 1, n_left
        i = left(k)
        e = eps_p(i) + de(i)
        inv_e = 1.0_rk/e
        ! from the last iterate: Newton's steps are small, so the series serves
        if (it > 1) pw(i) = pw(i)*power_ratio((de(i) - de_pw(i))*inv_e_pw(i), mat%jc_n)
        de_pw(i) = de(i)          ! the increment pw belongs to
        inv_e_pw(i) = inv_e
        h = mat%jc_a + mat%jc_b*pw(i)
        if (plastic_rate) then
          r(i) = 1.0_rk
          if (de(i) > de_rate1) r(i) = 1.0_rk + mat%jc_c*log(de(i)/de_rate1)
        end if
        f = q_trial(i) - g3*de(i) - soft(i)*h*r(i)
        ! converged to round-off of the residual (a relative step test alone
        ! never ends for tiny increments, whose residual noise dominates)
        if (abs(f) <= 1.0e-13_rk*q_trial(i)) cycle
        fp = -g3 - soft(i)*r(i)*mat%jc_b*mat%jc_n*pw(i)*inv_e
        if (plastic_rate .and. de(i) > de_rate1) fp = fp - soft(i)*h*mat%jc_c/de(i)
        call newton_step(de(i), f, fp, lo(i), hi(i), 1.0e-12_rk, done)
        if (done) cycle
        n_next = n_next + 1
        left(n_next) = i
      end do
      n_left = n_next
    end do
    do k = 1, n
      i = el(k)
      if (soft(i) <= 0.0_rk .or. (mat%jc_b <= 0.0_rk .and. .not. plastic_rate)) cycle
      ! on the yield surface by construction of the return
      sy(i) = q_trial(i) - g3*de(i)
      ! the power of the last iteration, moved by its step if it moved de
      if (de(i) /= de_pw(i)) pw(i) = pw(i)*power_ratio((de(i) - de_pw(i))*inv_e_pw(i), mat%jc_n)
      hard(i) = mat%jc_a + mat%jc_b*pw(i)
    end do
  end subroutine

  !> (1 + x)^n for x > -1: the binomial series to x^6 where |x| < 0.02
  !> (first omitted term below 1e-13 relative for 0 < n < 2), the power
  !> otherwise.
  pure elemental real(rk) function power_ratio(x, n) result(r)
    real(rk), intent(in) :: x, n
    real(rk), parameter :: inv_k(6) = [1.0_rk, 1.0_rk/2, 1.0_rk/3, 1.0_rk/4, 1.0_rk/5, 1.0_rk/6]
    integer :: k
    if (abs(x) < 0.02_rk) then
      r = 1.0_rk
      do k = 6, 1, -1
        r = 1.0_rk + x*(n - real(k - 1, rk))*inv_k(k)*r
      end do
    else
      r = (1.0_rk + x)**n
    end if
  end function

  !> Thermal softening after the temperature rose from temp_old (where it
  !> was soft_old) to temp_new, with the same series for small changes.
  pure elemental real(rk) function thermal_softening_update(mat, soft_old, temp_old, temp_new) result(soft)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: soft_old, temp_old, temp_new
    real(rk) :: ts_old, ts_new
    if (mat%strength /= strength_johnson_cook) then
      soft = 1.0_rk
      return
    end if
    ts_old = (temp_old - mat%t_room)/(mat%t_melt - mat%t_room)
    ts_new = (temp_new - mat%t_room)/(mat%t_melt - mat%t_room)
    if (ts_old > 0.0_rk .and. ts_new > 0.0_rk .and. ts_new < 1.0_rk .and. soft_old < 1.0_rk) then
      soft = 1.0_rk - (1.0_rk - soft_old)*power_ratio(ts_new/ts_old - 1.0_rk, mat%jc_m)
    else
      soft = jc_thermal_factor(mat, temp_new)
    end if
  end function

  pure real(rk) function dot6(a, b)
    real(rk), intent(in) :: a(6), b(6)
    dot6 = a(1)*b(1) + a(2)*b(2) + a(3)*b(3) + 2.0_rk*(a(4)*b(4) + a(5)*b(5) + a(6)*b(6))
  end function
end module udar_strength
