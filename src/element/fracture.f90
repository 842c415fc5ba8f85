!> Fracture by plastic strain intensity (the seed paper's criterion),
!> Johnson-Cook damage and spall; the element states and the pure kernels
!> the element pass calls. Fractured material carries no tension and no
!> shear; an eroded element is gone from the mesh (its mass stays at its
!> nodes). No state, no I/O.
module udar_fracture
  use udar_kinds, only: rk
  use udar_config, only: material_cfg_t, fracture_none, fracture_plastic_strain, fracture_johnson_cook
  implicit none
  private
  public :: fracture_update, jc_fracture_strain, fracture_enabled, erosion_enabled, deviatoric_rate

  integer, parameter, public :: el_intact = 0, el_fractured = 1, el_eroded = 2
  !> why an element was eroded (counters in the log): fractured and
  !> strained past eps_erode, its step collapsed, inverted within a step,
  !> or intact and strained past eps_convert (a particle with strength)
  integer, parameter, public :: erode_strain = 1, erode_time_step = 2, erode_inverted = 3, erode_converted = 4, &
                                erode_reasons = 4

contains

  !> Whether a material can fracture at all (a criterion or a spall strength).
  pure logical function fracture_enabled(mat)
    type(material_cfg_t), intent(in) :: mat
    fracture_enabled = mat%fracture /= fracture_none .or. mat%p_spall > 0.0_rk
  end function

  !> Whether elements of a material are eroded (removed).
  elemental logical function erosion_enabled(mat)
    type(material_cfg_t), intent(in) :: mat
    erosion_enabled = mat%eps_erode > 0.0_rk
  end function

  !> Equivalent deviatoric strain rate sqrt(2/3 D':D') of strain rate d
  !> (xx,yy,zz,xy,yz,zx; tensor shear components).
  pure real(rk) function deviatoric_rate(d) result(r)
    real(rk), intent(in) :: d(6)
    real(rk) :: tr3
    tr3 = (d(1) + d(2) + d(3))/3.0_rk
    r = sqrt(2.0_rk/3.0_rk*((d(1) - tr3)**2 + (d(2) - tr3)**2 + (d(3) - tr3)**2 &
                            + 2.0_rk*(d(4)**2 + d(5)**2 + d(6)**2)))
  end function

  !> Johnson-Cook (1985) strain to fracture at stress triaxiality
  !> triax = sigma_m / sigma_vm = -p / sigma_vm, plastic strain rate rate
  !> (1/s) and temperature temp (K):
  !>   eps_f = [D1 + D2 exp(D3 triax)] [1 + D4 ln(max(rate/rate0, 1))] [1 + D5 T*]
  pure real(rk) function jc_fracture_strain(mat, triax, rate, temp) result(eps_f)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: triax, rate, temp
    real(rk) :: t_star
    eps_f = mat%jc_d1 + mat%jc_d2*exp(min(mat%jc_d3*triax, 50.0_rk))
    eps_f = eps_f*(1.0_rk + mat%jc_d4*log(max(rate/mat%jc_rate0, 1.0_rk)))
    if (mat%jc_d5 /= 0.0_rk) then
      t_star = min(max((temp - mat%t_room)/(mat%t_melt - mat%t_room), 0.0_rk), 1.0_rk)
      eps_f = eps_f*(1.0_rk + mat%jc_d5*t_star)
    end if
    eps_f = max(eps_f, tiny(1.0_rk))
  end function

  !> Damage and fracture of one intact element after its stress update:
  !> d_eps plastic strain increment of the step over dt, eps_p the plastic
  !> strain after it, s_vm the von Mises stress, p the pressure, temp the
  !> temperature. damage: eps_p / eps_f (plastic_strain) or the Johnson-Cook
  !> sum of d_eps / eps_f(triax, rate, T). The element fractures when the
  !> damage reaches 1 or the mean stress falls below -p_spall (spall).
  pure subroutine fracture_update(mat, dt, d_eps, eps_p, s_vm, p, temp, damage, fractured)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: dt, d_eps, eps_p, s_vm, p, temp
    real(rk), intent(inout) :: damage
    logical, intent(out) :: fractured
    real(rk) :: triax
    select case (mat%fracture)
    case (fracture_plastic_strain)
      damage = eps_p/mat%eps_f
    case (fracture_johnson_cook)
      if (d_eps > 0.0_rk) then
        ! pure pressure with no deviator: the most compressive/tensile limit
        triax = sign(1.5_rk, -p)
        if (s_vm > 0.0_rk) triax = max(min(-p/s_vm, 1.5_rk), -1.5_rk)
        damage = damage + d_eps/jc_fracture_strain(mat, triax, d_eps/dt, temp)
      end if
    end select
    fractured = damage >= 1.0_rk
    if (mat%p_spall > 0.0_rk) fractured = fractured .or. p < -mat%p_spall
  end subroutine
end module udar_fracture
