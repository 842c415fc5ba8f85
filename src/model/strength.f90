!> Deviatoric stress update: Jaumann rotation (Hughes-Winget / Cayley form,
!> exactly orthogonal), hypoelastic trial step and radial return to the von
!> Mises surface. Pure; one element per call, the driver loops.
module udar_strength
  use udar_kinds, only: rk
  use udar_config, only: material_cfg_t, strength_none, strength_elastic, &
      strength_perfectly_plastic, strength_linear_hardening, strength_johnson_cook
  implicit none
  private
  public :: rotate_deviator, deviatoric_update, yield_stress, von_mises

contains

  !> s <- R s R^T with R = (I - dt W/2)^-1 (I + dt W/2); w = (W_xy, W_yz, W_zx).
  pure subroutine rotate_deviator(dt, w, s)
    real(rk), intent(in) :: dt, w(3)
    real(rk), intent(inout) :: s(6)
    real(rk) :: om(3,3), r(3,3), sm(3,3), o2, c
    om = 0.0_rk
    om(1,2) = 0.5_rk*dt*w(1); om(2,1) = -om(1,2)
    om(2,3) = 0.5_rk*dt*w(2); om(3,2) = -om(2,3)
    om(3,1) = 0.5_rk*dt*w(3); om(1,3) = -om(3,1)
    o2 = om(1,2)**2 + om(2,3)**2 + om(3,1)**2
    c = 2.0_rk/(1.0_rk + o2)
    r = c*(om + matmul(om, om))
    r(1,1) = r(1,1) + 1.0_rk; r(2,2) = r(2,2) + 1.0_rk; r(3,3) = r(3,3) + 1.0_rk
    sm(1,1) = s(1); sm(2,2) = s(2); sm(3,3) = s(3)
    sm(1,2) = s(4); sm(2,1) = s(4); sm(2,3) = s(5); sm(3,2) = s(5); sm(3,1) = s(6); sm(1,3) = s(6)
    sm = matmul(r, matmul(sm, transpose(r)))
    s(1) = sm(1,1); s(2) = sm(2,2); s(3) = sm(3,3)
    s(4) = sm(1,2); s(5) = sm(2,3); s(6) = sm(3,1)
  end subroutine

  pure real(rk) function von_mises(s) result(q)
    real(rk), intent(in) :: s(6)
    q = sqrt(1.5_rk*(s(1)**2 + s(2)**2 + s(3)**2 + 2.0_rk*(s(4)**2 + s(5)**2 + s(6)**2)))
  end function

  !> Flow stress of the material at plastic strain eps_p, equivalent strain
  !> rate rate (1/s) and temperature temp (K).
  pure real(rk) function yield_stress(mat, eps_p, rate, temp) result(sy)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: eps_p, rate, temp
    real(rk) :: tstar
    select case (mat%strength)
    case (strength_perfectly_plastic)
      sy = mat%yield_stress
    case (strength_linear_hardening)
      sy = mat%yield_stress + mat%hardening_modulus*eps_p
    case (strength_johnson_cook)
      tstar = (temp - mat%t_room)/(mat%t_melt - mat%t_room)
      sy = (mat%jc_a + mat%jc_b*max(eps_p, 0.0_rk)**mat%jc_n) &
         * (1.0_rk + mat%jc_c*log(max(rate/mat%jc_rate0, 1.0_rk)))
      if (tstar >= 1.0_rk) then
        sy = 0.0_rk
      else if (tstar > 0.0_rk) then
        sy = sy*(1.0_rk - tstar**mat%jc_m)
      end if
    case default
      sy = huge(1.0_rk)
    end select
  end function

  !> One step of the deviatoric stress s (already rotated) under the strain
  !> rate d (xx,yy,zz,xy,yz,zx) over dt. Returns the plastic strain increment
  !> and the deviatoric and plastic work per unit volume (J/m3).
  pure subroutine deviatoric_update(mat, dt, d, temp, s, eps_p, d_eps_p, w_dev, w_plastic)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: dt, d(6), temp
    real(rk), intent(inout) :: s(6), eps_p
    real(rk), intent(out) :: d_eps_p, w_dev, w_plastic
    real(rk) :: dd(6), s_old(6), tr3, g, q_trial, sy, rate, scale
    d_eps_p = 0.0_rk; w_plastic = 0.0_rk
    if (mat%strength == strength_none) then
      s = 0.0_rk; w_dev = 0.0_rk
      return
    end if
    tr3 = (d(1) + d(2) + d(3))/3.0_rk
    dd = d; dd(1:3) = dd(1:3) - tr3
    g = mat%shear_modulus
    s_old = s
    s = s + 2.0_rk*g*dt*dd
    if (mat%strength /= strength_elastic) then
      q_trial = von_mises(s)
      rate = sqrt(2.0_rk/3.0_rk*(dd(1)**2 + dd(2)**2 + dd(3)**2 + 2.0_rk*(dd(4)**2 + dd(5)**2 + dd(6)**2)))
      sy = yield_stress(mat, eps_p, rate, temp)
      if (q_trial > sy) then
        d_eps_p = plastic_increment(mat, q_trial, eps_p, rate, temp)
        sy = yield_stress(mat, eps_p + d_eps_p, rate, temp)
        scale = sy/q_trial
        s = s*scale
        eps_p = eps_p + d_eps_p
        w_plastic = sy*d_eps_p
      end if
    end if
    w_dev = 0.5_rk*dt*dot6(s_old + s, dd)
  end subroutine

  !> Solves q_trial - 3 G de = sigma_y(eps_p + de) for de >= 0: closed form
  !> for linear hardening, safeguarded Newton (bisection fallback) otherwise.
  pure real(rk) function plastic_increment(mat, q_trial, eps_p, rate, temp) result(de)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: q_trial, eps_p, rate, temp
    real(rk) :: g3, lo, hi, f, fp, h, de_new, sy
    integer :: it
    g3 = 3.0_rk*mat%shear_modulus
    select case (mat%strength)
    case (strength_perfectly_plastic)
      de = (q_trial - mat%yield_stress)/g3
    case (strength_linear_hardening)
      de = (q_trial - mat%yield_stress - mat%hardening_modulus*eps_p)/(g3 + mat%hardening_modulus)
    case default
      lo = 0.0_rk; hi = q_trial/g3
      de = 0.5_rk*(q_trial - yield_stress(mat, eps_p, rate, temp))/g3
      do it = 1, 50
        sy = yield_stress(mat, eps_p + de, rate, temp)
        f = q_trial - g3*de - sy
        if (f > 0.0_rk) then
          lo = de
        else
          hi = de
        end if
        ! slope by a one-sided difference: robust where eps^n has an infinite slope at 0
        h = max(1.0e-8_rk, 1.0e-6_rk*de)
        fp = -g3 - (yield_stress(mat, eps_p + de + h, rate, temp) - sy)/h
        de_new = de - f/fp
        if (de_new <= lo .or. de_new >= hi) de_new = 0.5_rk*(lo + hi)
        if (abs(de_new - de) <= 1.0e-12_rk*max(de_new, 1.0e-12_rk)) then
          de = de_new
          exit
        end if
        de = de_new
      end do
    end select
    de = max(de, 0.0_rk)
  end function

  pure real(rk) function dot6(a, b)
    real(rk), intent(in) :: a(6), b(6)
    dot6 = a(1)*b(1) + a(2)*b(2) + a(3)*b(3) + 2.0_rk*(a(4)*b(4) + a(5)*b(5) + a(6)*b(6))
  end function
end module udar_strength
