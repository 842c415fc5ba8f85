!> Flow stress models beyond Johnson-Cook (issue 16): Zerilli-Armstrong,
!> Steinberg-Cochran-Guinan (with Lund's rate term), the Mechanical
!> Threshold Stress and Preston-Tonks-Wallace, the shear
!> modulus and melt temperature models that go with them, and their radial
!> returns. Pure kernels; doc/theory.md section 16 states the equations and
!> sources.
module udar_flow_models
  use udar_kinds, only: rk
  use udar_config, only: material_cfg_t, strength_zerilli_armstrong, strength_steinberg_guinan, strength_ptw, &
      strength_steinberg_lund, shear_steinberg_guinan, shear_mts, shear_ptw, melt_steinberg_guinan
  implicit none
  private
  public :: melt_temperature, shear_modulus_at, model_flow_stress, model_return, newton_step, &
            mts_flow_stress, mts_return, steinberg_lund_thermal
  !> strain rates below this count as it in the MTS model's logarithms (1/s)
  real(rk), parameter :: mts_rate_floor = 1.0e-6_rk
  real(rk), parameter :: avogadro = 6.02214076e23_rk    !< 1/mol
  real(rk), parameter :: pi = 3.14159265358979324_rk
  real(rk), parameter :: boltzmann = 1.380649e-23_rk    !< J/K

contains

  !> The melt temperature (K) at eta = rho/rho0: t_melt, or with
  !> melt_model = 'steinberg_guinan' Lindemann's law as Steinberg, Cochran
  !> and Guinan (1980, eq. 4) write it,
  !>   T_m = t_melt exp(2 a (1 - 1/eta)) eta^(2 (gamma0 - a - 1/3)).
  !> huge() when the material has no t_melt (no melting).
  pure elemental real(rk) function melt_temperature(mat, eta) result(tm)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: eta
    tm = huge(1.0_rk)
    if (mat%t_melt <= 0.0_rk) return
    tm = mat%t_melt
    if (mat%melt_model == melt_steinberg_guinan) &
      tm = mat%t_melt*exp(2.0_rk*mat%melt_a*(1.0_rk - 1.0_rk/eta))*eta**(2.0_rk*(mat%gamma0 - mat%melt_a - 1.0_rk/3.0_rk))
  end function

  !> The shear modulus (Pa) at pressure p (Pa), temperature temp (K) and
  !> eta = rho/rho0: shear_modulus, or with shear_model = 'steinberg_guinan'
  !> (Steinberg, Cochran and Guinan 1980, eq. 2)
  !>   G = G0 (1 + A p eta^(-1/3) - B (T - t0)),  not below 0.
  pure elemental real(rk) function shear_modulus_at(mat, p, temp, eta) result(g)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: p, temp, eta
    g = mat%shear_modulus
    select case (mat%shear_model)
    case (shear_steinberg_guinan)
      g = max(mat%shear_modulus*(1.0_rk + mat%sg_a*p/eta**(1.0_rk/3.0_rk) - mat%sg_b*(temp - mat%sg_t0)), 0.0_rk)
    case (shear_mts)
      ! Varshni's form, G0 at 0 K (Follansbee and Kocks 1988)
      if (temp > 0.0_rk) g = max(mat%shear_modulus - mat%mts_d/(exp(mat%mts_t0/temp) - 1.0_rk), 0.0_rk)
    case (shear_ptw)
      ! Preston, Tonks and Wallace (2003): linear in the homologous temperature
      g = max(mat%shear_modulus*(1.0_rk - mat%ptw_alpha*temp/melt_temperature(mat, eta)), 0.0_rk)
    end select
  end function

  !> The flow stress (Pa) of the models of this module and its slope
  !> d(sigma)/d(eps_p) at plastic strain eps_p, equivalent strain rate
  !> rate (1/s), temperature temp (K), melt temperature t_m (K) and shear
  !> modulus ratio g_ratio = G/G0:
  !>   Zerilli-Armstrong (1987, eqs. 8 and 11 in one form: c1 = c5 = 0 for
  !>   FCC metals, c2 = 0 for BCC)
  !>     sigma = c0 + (c1 + c2 eps_p^1/2) exp(-c3 T + c4 T ln(rate*)) + c5 eps_p^n,
  !>     rate* = max(rate, rate0)/rate0;
  !>   Steinberg-Cochran-Guinan (1980, eq. 1)
  !>     Y = min(y0 (1 + beta (eps_p + eps_i))^n, ymax) G/G0;
  !>   Steinberg-Lund (1989, eq. 6) adds the thermally activated part
  !>     Y = (Y_T(rate, T) + min(y0 (1 + beta (eps_p + eps_i))^n, ymax)) G/G0
  !>   with Y_T from steinberg_lund_thermal;
  !>   Preston-Tonks-Wallace (2003), at density rho: ptw_flow_stress.
  !> Above the melt temperature all are 0 (no strength).
  pure subroutine model_flow_stress(mat, eps_p, rate, temp, t_m, g_ratio, rho, sy, slope)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: eps_p, rate, temp, t_m, g_ratio, rho
    real(rk), intent(out) :: sy, slope
    real(rk) :: th, root
    sy = 0.0_rk
    slope = 0.0_rk
    if (temp >= t_m) return
    select case (mat%strength)
    case (strength_zerilli_armstrong)
      th = exp(temp*(mat%za_c4*log(max(rate, mat%za_rate0)/mat%za_rate0) - mat%za_c3))
      root = sqrt(max(eps_p, 0.0_rk))
      sy = mat%za_c0 + (mat%za_c1 + mat%za_c2*root)*th
      if (root > 0.0_rk) slope = 0.5_rk*mat%za_c2*th/root
      if (mat%za_c5 /= 0.0_rk .and. eps_p > 0.0_rk) then
        sy = sy + mat%za_c5*eps_p**mat%za_n
        slope = slope + mat%za_c5*mat%za_n*eps_p**(mat%za_n - 1.0_rk)
      end if
    case (strength_steinberg_guinan)
      call sg_hardening(mat, eps_p, 0.0_rk, g_ratio, sy, slope)
    case (strength_steinberg_lund)
      call sg_hardening(mat, eps_p, steinberg_lund_thermal(mat, rate, temp), g_ratio, sy, slope)
    case (strength_ptw)
      call ptw_flow_stress(mat, eps_p, rate, temp/t_m, g_ratio*mat%shear_modulus, rho, sy, slope)
    end select
  end subroutine

  !> Steinberg-Guinan's flow stress (y_t + min(y0 (1 + beta (eps_p +
  !> eps_i))^n, ymax)) g_ratio and its slope in eps_p; y_t is Lund's
  !> thermally activated part (0 without it).
  pure subroutine sg_hardening(mat, eps_p, y_t, g_ratio, sy, slope)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: eps_p, y_t, g_ratio
    real(rk), intent(out) :: sy, slope
    real(rk) :: y
    slope = 0.0_rk
    y = mat%sg_y0*(1.0_rk + mat%sg_beta*(eps_p + mat%sg_eps_i))**mat%sg_n
    if (y < mat%sg_ymax) then
      slope = g_ratio*mat%sg_n*mat%sg_beta*y/(1.0_rk + mat%sg_beta*(eps_p + mat%sg_eps_i))
    else
      y = mat%sg_ymax
    end if
    sy = (y_t + y)*g_ratio
  end subroutine

  !> Lund's thermally activated stress Y_T (Pa) at strain rate rate (1/s)
  !> and temperature temp (K): the root in (0, Y_P] of
  !>   1/rate = exp(2 U_k/(k T) (1 - Y_T/Y_P)^2)/C1 + C2/Y_T
  !> (Steinberg and Lund 1989, eq. 5; rates below 1e-6/s count as
  !> 1e-6/s, temperatures below 1 K as 1 K). Both times on the right fall
  !> as Y_T grows, so the root is unique; rates at or above
  !> 1/(1/C1 + C2/Y_P), which the Peierls barrier cannot hold back, give
  !> Y_P. Solved for the logarithm of the right side (it stays finite
  !> where the exponential would overflow) by Newton's iteration kept in
  !> its bracket.
  pure real(rk) function steinberg_lund_thermal(mat, rate, temp) result(y_t)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: rate, temp
    real(rk) :: a, log_rate, lo, hi, f, fp
    integer :: it
    logical :: done
    a = 2.0_rk*mat%sl_uk/(boltzmann*max(temp, 1.0_rk))
    log_rate = log(max(rate, mts_rate_floor))
    y_t = mat%sl_yp
    call log_time(y_t, f, fp)
    if (f >= 0.0_rk) return
    lo = 0.0_rk
    hi = mat%sl_yp
    if (mat%sl_c2 <= 0.0_rk) then
      ! no drag: a rate that thermal activation alone reaches needs no stress
      call log_time(tiny(1.0_rk)*mat%sl_yp, f, fp)
      if (f <= 0.0_rk) then
        y_t = 0.0_rk
        return
      end if
    end if
    y_t = 0.5_rk*mat%sl_yp
    do it = 1, 200
      call log_time(y_t, f, fp)
      if (abs(f) <= 1.0e-13_rk) exit
      call newton_step(y_t, f, fp, lo, hi, 1.0e-14_rk, done)
      if (done) exit
    end do

  contains

    !> f = ln(rate) + ln(t_a + t_d) at Y_T = y, t_a and t_d the two times
    !> of the rate law (f falls in y and is 0 at the root), and its slope
    !> fp in y.
    pure subroutine log_time(y, f, fp)
      real(rk), intent(in) :: y
      real(rk), intent(out) :: f, fp
      real(rk) :: la, ld, top, wa, wd
      la = a*(1.0_rk - y/mat%sl_yp)**2 - log(mat%sl_c1)
      ld = -huge(1.0_rk)
      if (mat%sl_c2 > 0.0_rk) ld = log(mat%sl_c2/y)
      top = max(la, ld)
      wa = exp(la - top)
      wd = exp(ld - top)
      f = log_rate + top + log(wa + wd)
      fp = (-wa*2.0_rk*a*(1.0_rk - y/mat%sl_yp)/mat%sl_yp - wd/y)/(wa + wd)
    end subroutine
  end function

  !> Preston, Tonks and Wallace (2003, eqs. 5-12): at plastic strain psi,
  !> rate, homologous temperature t_hat = T/T_m, shear modulus g and density
  !> rho, with xi = 1/2 (4 pi rho N_A/(3 M))^(1/3) (g/rho)^(1/2) and
  !> e = rate/xi (rates below 1e-6/s count as 1e-6/s),
  !>   tau_s = max(s0 - (s0 - sinf) erf(kappa t_hat ln(gamma/e)), s0 (e/gamma)^beta)
  !>   tau_y = max(y0 - (y0 - yinf) erf(...), min(y1 (e/gamma)^y2, s0 (e/gamma)^beta))
  !>   tau   = tau_s + (s0 - tau_y)/p ln(1 - [1 - exp(-p d/a)] exp(-p theta psi/(a (exp(p d/a) - 1)))),
  !> a = s0 - tau_y, d = tau_s - tau_y (p -> 0: tau_s - d exp(-theta psi/d); tau = tau_s
  !> when d <= 0), and the flow stress 2 tau g with its slope in psi.
  pure subroutine ptw_flow_stress(mat, psi, rate, t_hat, g, rho, sy, slope)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: psi, rate, t_hat, g, rho
    real(rk), intent(out) :: sy, slope
    real(rk) :: ts, ty
    call ptw_saturation(mat, rate, t_hat, g, rho, ts, ty)
    call ptw_hardening(mat, psi, ts, ty, g, sy, slope)
  end subroutine

  !> PTW's saturation and yield stresses tau_s, tau_y (over G) at a rate,
  !> homologous temperature, shear modulus and density: what the return
  !> holds fixed.
  pure subroutine ptw_saturation(mat, rate, t_hat, g, rho, ts, ty)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: rate, t_hat, g, rho
    real(rk), intent(out) :: ts, ty
    real(rk) :: xi, e, arg, er
    xi = 0.5_rk*(4.0_rk*pi*rho*avogadro/(3.0_rk*mat%ptw_molar_mass))**(1.0_rk/3.0_rk)*sqrt(g/rho)
    e = max(rate, mts_rate_floor)/xi
    arg = mat%ptw_kappa*t_hat*log(mat%ptw_gamma/e)
    er = erf(arg)
    ts = max(mat%ptw_s0 - (mat%ptw_s0 - mat%ptw_sinf)*er, mat%ptw_s0*(e/mat%ptw_gamma)**mat%ptw_beta)
    ty = max(mat%ptw_y0 - (mat%ptw_y0 - mat%ptw_yinf)*er, &
             min(mat%ptw_y1*(e/mat%ptw_gamma)**mat%ptw_y2, mat%ptw_s0*(e/mat%ptw_gamma)**mat%ptw_beta))
  end subroutine

  !> PTW's flow stress 2 tau g at plastic strain psi between ts and ty, and
  !> its slope.
  pure subroutine ptw_hardening(mat, psi, ts, ty, g, sy, slope)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: psi, ts, ty, g
    real(rk), intent(out) :: sy, slope
    real(rk) :: a, d, big, u, tau, dtau
    d = ts - ty
    if (d <= 0.0_rk) then
      tau = ts
      dtau = 0.0_rk
    else if (mat%ptw_p <= 0.0_rk) then
      u = exp(-mat%ptw_theta*psi/d)
      tau = ts - d*u
      dtau = mat%ptw_theta*u
    else
      a = mat%ptw_s0 - ty
      big = exp(mat%ptw_p*d/a)
      u = exp(-mat%ptw_p*mat%ptw_theta*psi/(a*(big - 1.0_rk)))
      tau = ts + a/mat%ptw_p*log(1.0_rk - (1.0_rk - 1.0_rk/big)*u)
      dtau = mat%ptw_theta*u/(big*(1.0_rk - (1.0_rk - 1.0_rk/big)*u))
    end if
    sy = 2.0_rk*tau*g
    slope = 2.0_rk*dtau*g
  end subroutine

  !> The radial return of these models: the increment de >= 0 of plastic
  !> strain with
  !>   q_trial - 3 G de = sigma(eps_p + de)
  !> at the step's rate and temperature (fixed in the return, as for
  !> Johnson-Cook's total-rate form), and sy = sigma(eps_p + de). The left
  !> side falls strictly in de and the right side does not, so the root is
  !> bracketed by [0, q_trial/(3G)]: Newton's iteration from the
  !> no-hardening return, kept in the bracket by bisection. With no
  !> strength left (melt) de takes the whole trial deviator, q_trial/(3G).
  !> Called only where q_trial > sigma(eps_p) and g > 0.
  pure subroutine model_return(mat, g, q_trial, eps_p, rate, temp, t_m, g_ratio, rho, de, sy)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: g, q_trial, eps_p, rate, temp, t_m, g_ratio, rho
    real(rk), intent(out) :: de, sy
    real(rk) :: g3, lo, hi, f, slope, ts, ty, y_t
    integer :: it
    logical :: done
    g3 = 3.0_rk*g
    if (temp >= t_m) then
      ! melted: all of the trial deviator flows
      de = q_trial/g3
      sy = 0.0_rk
      return
    end if
    ! PTW's saturation stresses do not change in the return: once
    if (mat%strength == strength_ptw) call ptw_saturation(mat, rate, temp/t_m, g, rho, ts, ty)
    ! nor does Lund's thermally activated stress
    if (mat%strength == strength_steinberg_lund) y_t = steinberg_lund_thermal(mat, rate, temp)
    call flow(eps_p, sy, slope)
    lo = 0.0_rk
    hi = q_trial/g3
    de = min((q_trial - sy)/g3, hi)
    do it = 1, 100
      call flow(eps_p + de, sy, slope)
      f = q_trial - g3*de - sy
      if (abs(f) <= 1.0e-13_rk*q_trial) exit
      call newton_step(de, f, -(g3 + slope), lo, hi, 1.0e-14_rk, done)
      if (done) exit
    end do
    ! on the yield surface by construction of the return
    sy = q_trial - g3*de

  contains

    !> The flow stress and its slope at plastic strain e.
    pure subroutine flow(e, sig, dsig)
      real(rk), intent(in) :: e
      real(rk), intent(out) :: sig, dsig
      if (mat%strength == strength_ptw) then
        call ptw_hardening(mat, e, ts, ty, g, sig, dsig)
      else if (mat%strength == strength_steinberg_lund) then
        call sg_hardening(mat, e, y_t, g_ratio, sig, dsig)
      else
        call model_flow_stress(mat, e, rate, temp, t_m, g_ratio, rho, sig, dsig)
      end if
    end subroutine
  end subroutine

  !> The parts of the MTS flow stress that do not depend on the internal
  !> stress sigma_e, at rate (1/s), temperature temp (K) and shear modulus g:
  !>   fixed = sigma_a + S_i sigma_i G/G0,  s_e = S_e G/G0,
  !>   S_x = [1 - (k T/(g0x b^3 G) ln(rate0x/rate))^(1/qx)]^(1/px),
  !> the hardening rate theta0 = a0 + a1 ln rate + a2 rate^1/2 - a3 T (not
  !> below 0) and the saturation stress
  !>   sigma_es = sigma0es (rate/rate0es)^(k T/(g0es b^3 G)).
  pure subroutine mts_terms(mat, rate, temp, g, fixed, s_e, theta0, sigma_es)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: rate, temp, g
    real(rk), intent(out) :: fixed, s_e, theta0, sigma_es
    real(rk) :: r, ratio, kt
    r = max(rate, mts_rate_floor)
    ratio = g/mat%shear_modulus
    kt = mat%mts_kb3*temp/g
    fixed = mat%mts_sigma_a
    if (mat%mts_sigma_i > 0.0_rk) fixed = fixed + &
      mts_factor(kt/mat%mts_g0i*log(mat%mts_rate0i/r), mat%mts_pi, mat%mts_qi)*mat%mts_sigma_i*ratio
    s_e = mts_factor(kt/mat%mts_g0e*log(mat%mts_rate0e/r), mat%mts_pe, mat%mts_qe)*ratio
    theta0 = max(mat%mts_a0 + mat%mts_a1*log(r) + mat%mts_a2*sqrt(r) - mat%mts_a3*temp, 0.0_rk)
    sigma_es = mat%mts_sigma0es*(r/mat%mts_rate0es)**(kt/mat%mts_g0es)
  end subroutine

  !> [1 - x^(1/q)]^(1/p) for x >= 0 (1 for x < 0: faster than the reference
  !> rate), 0 once x^(1/q) >= 1.
  pure real(rk) function mts_factor(x, p, q) result(f)
    real(rk), intent(in) :: x, p, q
    real(rk) :: y
    y = max(x, 0.0_rk)**(1.0_rk/q)
    f = 0.0_rk
    if (y < 1.0_rk) f = (1.0_rk - y)**(1.0_rk/p)
  end function

  !> The MTS hardening rate d(sigma_e)/d(eps_p) = theta0 (1 - F) + theta_iv F,
  !> F = tanh(alpha X)/tanh(alpha), X = sigma_e/sigma_es (not below 0).
  pure real(rk) function mts_hardening(mat, sigma_e, theta0, sigma_es) result(theta)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: sigma_e, theta0, sigma_es
    real(rk) :: f
    f = tanh(mat%mts_alpha*sigma_e/sigma_es)/tanh(mat%mts_alpha)
    theta = max(theta0*(1.0_rk - f) + mat%mts_theta_iv*f, 0.0_rk)
  end function

  !> The MTS flow stress (Pa) at internal stress sigma_e; 0 at or above the
  !> melt temperature t_m.
  pure real(rk) function mts_flow_stress(mat, sigma_e, rate, temp, t_m, g) result(sy)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: sigma_e, rate, temp, t_m, g
    real(rk) :: fixed, s_e, theta0, sigma_es
    sy = 0.0_rk
    if (temp >= t_m .or. g <= 0.0_rk) return
    call mts_terms(mat, rate, temp, g, fixed, s_e, theta0, sigma_es)
    sy = fixed + s_e*sigma_e
  end function

  !> The MTS return: with the step's rate and temperature fixed and sigma_e
  !> advanced by the hardening rate of its start (sigma_e + theta de, not
  !> beyond the saturation sigma_es), the flow stress is linear in de and
  !>   q_trial - 3 G de = fixed + s_e (sigma_e + theta de)
  !> is solved in closed form; then de is taken again from the flow stress
  !> of the capped sigma_e, so the deviator ends on the surface. sigma_e
  !> (inout) is the element's internal stress. Melted: de = q_trial/(3G).
  !> Called only where q_trial exceeds the flow stress and g > 0.
  pure subroutine mts_return(mat, g, q_trial, rate, temp, t_m, sigma_e, de, sy)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: g, q_trial, rate, temp, t_m
    real(rk), intent(inout) :: sigma_e
    real(rk), intent(out) :: de, sy
    real(rk) :: fixed, s_e, theta0, sigma_es, theta, se_new
    if (temp >= t_m) then
      de = q_trial/(3.0_rk*g)
      sy = 0.0_rk
      return
    end if
    call mts_terms(mat, rate, temp, g, fixed, s_e, theta0, sigma_es)
    theta = mts_hardening(mat, sigma_e, theta0, sigma_es)
    de = (q_trial - fixed - s_e*sigma_e)/(3.0_rk*g + s_e*theta)
    se_new = min(sigma_e + theta*de, max(sigma_es, sigma_e))
    sy = fixed + s_e*se_new
    de = (q_trial - sy)/(3.0_rk*g)
    sigma_e = se_new
  end subroutine

  !> One step of a Newton iteration kept in its bracket, for a residual f
  !> that falls strictly in x (fp < 0): the bracket [lo, hi] shrinks to the
  !> side of x that the sign of f(x) keeps, and a Newton step that leaves
  !> it is replaced by the bisection.
  pure subroutine bracketed_newton(x, f, fp, lo, hi, x_new)
    real(rk), intent(in) :: x, f, fp
    real(rk), intent(inout) :: lo, hi
    real(rk), intent(out) :: x_new
    if (f > 0.0_rk) then
      lo = x
    else
      hi = x
    end if
    x_new = x - f/fp
    if (x_new <= lo .or. x_new >= hi) x_new = 0.5_rk*(lo + hi)
  end subroutine

  !> bracketed_newton's step taken: x moves to the new iterate, done when
  !> the step was at most rel_tol of it.
  pure subroutine newton_step(x, f, fp, lo, hi, rel_tol, done)
    real(rk), intent(inout) :: x, lo, hi
    real(rk), intent(in) :: f, fp, rel_tol
    logical, intent(out) :: done
    real(rk) :: x_new
    call bracketed_newton(x, f, fp, lo, hi, x_new)
    done = abs(x_new - x) <= rel_tol*x_new
    x = x_new
  end subroutine
end module udar_flow_models
