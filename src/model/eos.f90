!> Equations of state, written as p = A(J) + B(J) e with e the specific
!> internal energy (J/kg) and J = V/V0, so that the energy equation can be
!> solved exactly for e(n+1) (both EOS are linear in e).
module udar_eos
  use udar_kinds, only: rk
  implicit none
  private
  public :: eos_linear_ab, eos_mie_gruneisen_ab, eos_mie_gruneisen_c2, eos_mie_gruneisen_c2_block, eos_linear_c2

contains

  !> Linear: p = K mu, mu = rho/rho0 - 1 = 1/J - 1; no energy dependence.
  pure elemental subroutine eos_linear_ab(bulk, j, a, b)
    real(rk), intent(in) :: bulk, j
    real(rk), intent(out) :: a, b
    a = bulk*(1.0_rk/j - 1.0_rk)
    b = 0.0_rk
  end subroutine

  !> Square of the isentropic bulk sound speed of the linear EOS.
  pure elemental real(rk) function eos_linear_c2(bulk, rho0) result(c2)
    real(rk), intent(in) :: bulk, rho0
    c2 = bulk/rho0
  end function

  !> Mie-Grueneisen with a linear Us-up Hugoniot as reference curve and
  !> Gamma rho = gamma0 rho0 (Steinberg 1996; Meyers 1994 ch. 4):
  !>   eta = 1 - J = 1 - rho0/rho,
  !>   p_H = rho0 c0^2 eta / (1 - s eta)^2   (eta > 0),  rho0 c0^2 eta (eta <= 0),
  !>   p   = p_H (1 - gamma0 eta / 2) + gamma0 rho0 e.
  !> The compression is clamped at s eta <= 0.95 where the Hugoniot has its pole.
  pure elemental subroutine eos_mie_gruneisen_ab(rho0, c0, s, gamma0, j, a, b)
    real(rk), intent(in) :: rho0, c0, s, gamma0, j
    real(rk), intent(out) :: a, b
    real(rk) :: eta, ph
    eta = 1.0_rk - j
    ph = mg_hugoniot(rho0, c0, s, eta)
    a = ph*(1.0_rk - 0.5_rk*gamma0*eta)
    b = gamma0*rho0
  end subroutine

  !> Square of the isentropic sound speed: dp/drho at constant entropy,
  !> dA/drho + gamma0 rho0 p / rho^2, floored at c0^2/100 in deep tension
  !> (one element; eos_mie_gruneisen_c2_block does the work).
  pure elemental real(rk) function eos_mie_gruneisen_c2(rho0, c0, s, gamma0, j, p) result(c2)
    real(rk), intent(in) :: rho0, c0, s, gamma0, j, p
    real(rk) :: c2_one(1)
    call eos_mie_gruneisen_c2_block(rho0, c0, s, gamma0, 1, [j], [p], c2_one)
    c2 = c2_one(1)
  end function

  !> eos_mie_gruneisen_c2 of n elements at volume ratios j and pressures p:
  !> the formula is here, in the block loop, because the elemental was not
  !> inlined into its callers' loops (a call per element, no vectors).
  pure subroutine eos_mie_gruneisen_c2_block(rho0, c0, s, gamma0, n, j, p, c2)
    real(rk), intent(in) :: rho0, c0, s, gamma0
    integer, intent(in) :: n
    real(rk), intent(in) :: j(n), p(n)
    real(rk), intent(out) :: c2(n)
    real(rk) :: eta, ph, dph, rho, x
    integer :: i
    do i = 1, n
      eta = 1.0_rk - j(i)
      rho = rho0/j(i)
      ph = mg_hugoniot(rho0, c0, s, eta)
      ! branch-free (so that block loops vectorize): in tension x = 1 and the
      ! factor 1 leave rho0 c0^2 exact
      x = merge(1.0_rk - min(s*eta, 0.95_rk), 1.0_rk, eta > 0.0_rk)
      dph = rho0*c0**2*merge(1.0_rk + s*eta, 1.0_rk, eta > 0.0_rk)/x**3
      ! d eta / d rho = rho0 / rho^2
      c2(i) = (dph*(1.0_rk - 0.5_rk*gamma0*eta) - 0.5_rk*gamma0*ph)*rho0/rho**2 + gamma0*rho0*p(i)/rho**2
      c2(i) = max(c2(i), 0.01_rk*c0**2)
    end do
  end subroutine

  pure elemental real(rk) function mg_hugoniot(rho0, c0, s, eta) result(ph)
    real(rk), intent(in) :: rho0, c0, s, eta
    real(rk) :: x
    ! branch-free: in tension x = 1, and the division by 1 is exact
    x = merge(1.0_rk - min(s*eta, 0.95_rk), 1.0_rk, eta > 0.0_rk)
    ph = rho0*c0**2*eta/x**2
  end function
end module udar_eos
