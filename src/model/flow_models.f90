!> Flow stress models beyond Johnson-Cook (issue 16): Zerilli-Armstrong and
!> Steinberg-Cochran-Guinan, the shear modulus and melt temperature models
!> that go with them, and the implicit radial return they share. Pure
!> kernels; doc/theory.md section 16 states the equations and sources.
module udar_flow_models
  use udar_kinds, only: rk
  use udar_config, only: material_cfg_t, strength_zerilli_armstrong, strength_steinberg_guinan, &
      shear_steinberg_guinan, melt_steinberg_guinan
  implicit none
  private
  public :: melt_temperature, shear_modulus_at, model_flow_stress, model_return, bracketed_newton

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
    if (mat%shear_model == shear_steinberg_guinan) &
      g = max(mat%shear_modulus*(1.0_rk + mat%sg_a*p/eta**(1.0_rk/3.0_rk) - mat%sg_b*(temp - mat%sg_t0)), 0.0_rk)
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
  !>     Y = min(y0 (1 + beta (eps_p + eps_i))^n, ymax) G/G0.
  !> Above the melt temperature both are 0 (no strength).
  pure subroutine model_flow_stress(mat, eps_p, rate, temp, t_m, g_ratio, sy, slope)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: eps_p, rate, temp, t_m, g_ratio
    real(rk), intent(out) :: sy, slope
    real(rk) :: th, root, y
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
      y = mat%sg_y0*(1.0_rk + mat%sg_beta*(eps_p + mat%sg_eps_i))**mat%sg_n
      if (y < mat%sg_ymax) then
        slope = g_ratio*mat%sg_n*mat%sg_beta*y/(1.0_rk + mat%sg_beta*(eps_p + mat%sg_eps_i))
      else
        y = mat%sg_ymax
      end if
      sy = y*g_ratio
    end select
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
  pure subroutine model_return(mat, g, q_trial, eps_p, rate, temp, t_m, g_ratio, de, sy)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: g, q_trial, eps_p, rate, temp, t_m, g_ratio
    real(rk), intent(out) :: de, sy
    real(rk) :: g3, lo, hi, f, slope, de_new
    integer :: it
    g3 = 3.0_rk*g
    if (temp >= t_m) then
      ! melted: all of the trial deviator flows
      de = q_trial/g3
      sy = 0.0_rk
      return
    end if
    call model_flow_stress(mat, eps_p, rate, temp, t_m, g_ratio, sy, slope)
    lo = 0.0_rk
    hi = q_trial/g3
    de = min((q_trial - sy)/g3, hi)
    do it = 1, 100
      call model_flow_stress(mat, eps_p + de, rate, temp, t_m, g_ratio, sy, slope)
      f = q_trial - g3*de - sy
      if (abs(f) <= 1.0e-13_rk*q_trial) exit
      call bracketed_newton(de, f, -(g3 + slope), lo, hi, de_new)
      if (abs(de_new - de) <= 1.0e-14_rk*de_new) then
        de = de_new
        exit
      end if
      de = de_new
    end do
    ! on the yield surface by construction of the return
    sy = q_trial - g3*de
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
end module udar_flow_models
