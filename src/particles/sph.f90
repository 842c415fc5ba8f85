!> Kernels of the particles that failed material becomes (issue 15,
!> theory.md section 15): smoothed particle hydrodynamics in Monaghan's
!> symmetric form with the cubic B-spline kernel, the particles' pressure
!> from the material's EOS (failed material carries compression only;
!> particles that keep their strength carry tension too), and the
!> conversion of an element into a particle.
!> Pure procedures on plain arrays: no domain, no MPI, no module state.
!> Every pair sum runs over a pair list in the order given, so a caller
!> that gives the pairs in one order gets one result whatever its ranks.
module udar_sph
  use udar_kinds, only: rk, pi, block_size
  use udar_ordering, only: sort_ints
  use udar_config, only: material_cfg_t, eos_mie_gruneisen, shear_constant
  use udar_flow_models, only: shear_modulus_at
  use udar_hydro, only: volumetric_update
  use udar_eos, only: eos_linear_ab, eos_linear_c2, eos_mie_gruneisen_ab, eos_mie_gruneisen_c2
  use udar_strength, only: strength_block, thermal_softening_update, von_mises
  use udar_fracture, only: fracture_update, fracture_enabled
  implicit none
  private
  public :: spline_w, spline_dw, sph_forces, sph_rates, particle_update, particle_pressure, element_to_particle, sph_pairs, &
            smoothing_length, sph_stable_dt, particle_strength, wave_speed, artificial_stress, symmetric_eigen3, &
            shear_switch, hoop_forces, axisymmetric_rates

  !> Monaghan's viscosity's quadratic term's guard: mu = h v.r / (r^2 + eta2 h^2)
  real(rk), parameter :: eta2 = 0.01_rk
  !> the exponent n of the artificial stress's pair factor (W_ij/W(dp))^n (Monaghan 2000)
  integer, parameter :: art_exponent = 4

contains

  !> The cubic B-spline kernel (Monaghan and Lattanzio 1985) in dim = 2 or
  !> 3 dimensions, support 2h: W = sigma/h^dim f(r/h),
  !> f = 1 - 3/2 q^2 + 3/4 q^3 (q < 1), (2 - q)^3/4 (q < 2), 0 beyond;
  !> sigma = 1/pi (3D), 10/(7 pi) (2D), so that W integrates to one.
  pure elemental real(rk) function spline_w(r, h, dim) result(w)
    real(rk), intent(in) :: r, h
    integer, intent(in) :: dim
    w = spline_shape(r/h)*spline_sigma(dim)/h**dim
  end function

  !> f(q) of spline_w.
  pure elemental real(rk) function spline_shape(q) result(f)
    real(rk), intent(in) :: q
    if (q < 1.0_rk) then
      f = 1.0_rk - 1.5_rk*q**2 + 0.75_rk*q**3
    else if (q < 2.0_rk) then
      f = 0.25_rk*(2.0_rk - q)**3
    else
      f = 0.0_rk
    end if
  end function

  !> dW/dr of spline_w.
  pure elemental real(rk) function spline_dw(r, h, dim) result(dw)
    real(rk), intent(in) :: r, h
    integer, intent(in) :: dim
    real(rk) :: q
    q = r/h
    if (q < 1.0_rk) then
      dw = -3.0_rk*q + 2.25_rk*q**2
    else if (q < 2.0_rk) then
      dw = -0.75_rk*(2.0_rk - q)**2
    else
      dw = 0.0_rk
    end if
    dw = dw*spline_sigma(dim)/h**(dim + 1)
  end function

  pure real(rk) function spline_sigma(dim) result(sigma)
    integer, intent(in) :: dim
    sigma = merge(1.0_rk/pi, 10.0_rk/(7.0_rk*pi), dim == 3)
  end function

  !> A particle's smoothing length from its mass and density: factor times
  !> the side of the cube (square, 2D) of its volume.
  pure elemental real(rk) function smoothing_length(m, rho, factor, dim) result(h)
    real(rk), intent(in) :: m, rho, factor
    integer, intent(in) :: dim
    h = factor*(m/rho)**(1.0_rk/dim)
  end function

  !> The pressure and sound speed of a particle of material mat at density
  !> rho and specific internal energy e (J/kg): the element's EOS at
  !> J = rho0/rho; with tension false no tension (p >= 0: failed material,
  !> which still resists compression), with tension true (a particle that
  !> keeps its strength: unfailed material) the EOS's tension branch as an
  !> element has it. The sound speed at min(J, 1) (expanded failed material
  !> has no stiffness of its own: the EOS's tension branch, extrapolated
  !> far, would give sound speeds that grow without bound as particles
  !> part; and the step of a strong particle in tension is that of its
  !> uncompressed state).
  pure elemental subroutine particle_pressure(mat, rho, e, tension, p, c)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: rho, e
    logical, intent(in) :: tension
    real(rk), intent(out) :: p, c
    real(rk) :: j, a, b
    j = mat%rho0/rho
    if (mat%eos == eos_mie_gruneisen) then
      call eos_mie_gruneisen_ab(mat%rho0, mat%c0, mat%s, mat%gamma0, j, a, b)
      p = a + b*e
      if (.not. tension) p = max(p, 0.0_rk)
      c = sqrt(eos_mie_gruneisen_c2(mat%rho0, mat%c0, mat%s, mat%gamma0, min(j, 1.0_rk), max(p, 0.0_rk)))
    else
      call eos_linear_ab(mat%bulk_modulus, j, a, b)
      p = a + b*e
      if (.not. tension) p = max(p, 0.0_rk)
      c = sqrt(eos_linear_c2(mat%bulk_modulus, mat%rho0))
    end if
  end subroutine

  !> The accelerations of the particles over the pair list pairs(2,np)
  !> (each pair once, i /= j; pairs beyond 2 h_ij, h_ij = (h_i + h_j)/2,
  !> take no part):
  !>   dv_i/dt = sum_j m_j (s_i/rho_i^2 + s_j/rho_j^2
  !>                        - (p_i/rho_i^2 + p_j/rho_j^2 + Pi_ij) I) grad_i W_ij
  !> (Monaghan 1992, eq. 3.3; Libersky et al. 1993 for the deviatoric
  !> stress s(6,:), xx,yy,zz,xy,yz,zx, zero for material without strength),
  !> with Monaghan's viscosity Pi_ij = (-alpha cbar mu + beta mu^2)/rhobar
  !> for approaching pairs, mu = h_ij v_ij.x_ij/(x_ij^2 + 0.01 h_ij^2). The
  !> pair terms are equal and opposite: momentum is exact; angular momentum
  !> too where s = 0 (the terms are then along x_ij).
  !> Added to acc (zero it first); visc(k) keeps pair k's Pi for
  !> sph_rates; vsig is raised to each particle's largest signal speed
  !> c_i + c_j - 3 min(v_ij . x_ij/|x_ij|, 0) (Monaghan 1997), for the step.
  !> Axisymmetric (w present: each particle's radial weight 2 pi r, x(1) = r,
  !> x(2) the axis, masses per revolution): the same sums for the area
  !> density eta = rho w (Petschek and Libersky 1993), every rho^2 of a
  !> particle's term times its w and rhobar the mean of rho w, and gr(i)
  !> raised by sum_j m_j dW_ij/dr (the radial gradient of eta, for
  !> hoop_forces); the pairs then stay equal and opposite (momentum along
  !> the axis exact).
  pure subroutine sph_forces(dim, alpha, beta, np, pairs, x, v, m, rho, p, c, h, s, visc, acc, vsig, r_art, spacing, &
                             switch, w, gr)
    integer, intent(in) :: dim, np, pairs(:,:)
    real(rk), intent(in) :: alpha, beta
    real(rk), intent(in) :: x(:,:), v(:,:), m(:), rho(:), p(:), c(:), h(:), s(:,:)
    real(rk), intent(out) :: visc(:)
    real(rk), intent(inout) :: acc(:,:), vsig(:)
    real(rk), intent(in), optional :: r_art(:,:), spacing, switch(:), w(:)
    real(rk), intent(inout), optional :: gr(:)
    integer :: k, i, j
    real(rk) :: g(3), vij(3), vr, d, mu, coef, speed, hij, a(6), f(3), wi, wj
    ! (the plane and 3D weights are 1: a product by 1 is exact, the results are theirs to the bit)
    wi = 1
    wj = 1
    do k = 1, np
      i = pairs(1,k)
      j = pairs(2,k)
      call pair_gradient(dim, x(:,i), x(:,j), h(i), h(j), g, d, hij)
      visc(k) = 0
      if (all(g == 0.0_rk)) cycle
      if (present(w)) then
        wi = w(i)
        wj = w(j)
        gr(i) = gr(i) + m(j)*g(1)
        gr(j) = gr(j) - m(i)*g(1)
      end if
      vij = v(:,i) - v(:,j)
      vr = dot_product(vij, x(:,i) - x(:,j))
      if (vr < 0.0_rk) then
        mu = hij*vr/(d**2 + eta2*hij**2)
        visc(k) = (-alpha*0.5_rk*(c(i) + c(j))*mu + beta*mu**2)/(0.5_rk*(rho(i)*wi + rho(j)*wj))
        if (present(switch)) visc(k) = visc(k)*0.5_rk*(switch(i) + switch(j))
      end if
      coef = p(i)/(rho(i)**2*wi) + p(j)/(rho(j)**2*wj) + visc(k)
      acc(:,i) = acc(:,i) - (m(j)*coef)*g
      acc(:,j) = acc(:,j) + (m(i)*coef)*g
      if (any(s(:,i) /= 0.0_rk) .or. any(s(:,j) /= 0.0_rk)) then
        a = s(:,i)/(rho(i)**2*wi) + s(:,j)/(rho(j)**2*wj)
        f = [a(1)*g(1) + a(4)*g(2) + a(6)*g(3), a(4)*g(1) + a(2)*g(2) + a(5)*g(3), a(6)*g(1) + a(5)*g(2) + a(3)*g(3)]
        acc(:,i) = acc(:,i) + m(j)*f
        acc(:,j) = acc(:,j) - m(i)*f
      end if
      if (present(r_art)) then
        if (any(r_art(:,i) /= 0.0_rk) .or. any(r_art(:,j) /= 0.0_rk)) then
          f = art_pair_force(d, hij, spacing, r_art(:,i) + r_art(:,j), g)
          acc(:,i) = acc(:,i) + m(j)*f
          acc(:,j) = acc(:,j) - m(i)*f
        end if
      end if
      speed = c(i) + c(j) - 3.0_rk*min(vr/d, 0.0_rk)
      vsig(i) = max(vsig(i), speed)
      vsig(j) = max(vsig(j), speed)
    end do
  end subroutine

  !> The rates of the particles' density and viscous heating over the
  !> pairs of sph_forces (its visc), at the velocities v the forces' step
  !> has just given (v^{n+1/2}), the kernel's gradient at the middle of the
  !> step, x + dt/2 v (at x^n the density would lag the positions by half
  !> a step: a head-on pair then lost 0.9 % of its energy at Courant 0.2,
  !> in proportion to the step):
  !>   drho_i/dt = sum_j m_j v_ij . grad_i W_ij            (Monaghan 1992, eq. 2.17),
  !>   heat_i    = 1/2 sum_j m_j Pi_ij v_ij . grad_i W_ij  (J/(kg s), >= 0),
  !> so that de_i/dt = p_i/rho_i^2 drho_i/dt + heat_i (the thermodynamic
  !> form of eq. 3.7, which particle_update integrates with the EOS as the
  !> elements do), and the sums of the velocity gradient
  !>   grad_i    = sum_j m_j v_ij (x) grad_i W_ij   (L_i = dv/dx = -grad_i/rho_i,
  !> stored column by column, grad(a + 3(b-1)) for dv_a/dx_b; the same
  !> estimate as the continuity equation's: drho_i/dt = -rho_i tr L_i).
  !> For the same v and positions (dt = 0),
  !> sum_i m_i (v_i . dv_i/dt + de_i/dt) = 0 with
  !> de_i/dt = p_i/rho_i^2 drho_i/dt + heat_i + s_i : L_i / rho_i: the
  !> internal energy gains what the stresses and the viscosity take from
  !> the motion. Added to drho, heat and grad (zero them first); grad only
  !> when asked for (particles that keep their strength: no work otherwise).
  !> Axisymmetric, gr(i) is raised by sum_j m_j dW_ij/dr at the middle of
  !> the step as well, and axisymmetric_rates then makes these sums the
  !> area density's and adds the hoop rate.
  pure subroutine sph_rates(dim, dt, np, pairs, x, v, m, h, visc, drho, heat, grad, r_art, spacing, gr)
    integer, intent(in) :: dim, np, pairs(:,:)
    real(rk), intent(in) :: dt, x(:,:), v(:,:), m(:), h(:), visc(:)
    real(rk), intent(inout) :: drho(:), heat(:)
    real(rk), intent(inout), optional :: grad(:,:)
    real(rk), intent(in), optional :: r_art(:,:), spacing
    real(rk), intent(inout), optional :: gr(:)
    integer :: k, i, j
    real(rk) :: g(3), d, hij, vg, vij(3), work
    do k = 1, np
      i = pairs(1,k)
      j = pairs(2,k)
      call pair_gradient(dim, x(:,i) + (0.5_rk*dt)*v(:,i), x(:,j) + (0.5_rk*dt)*v(:,j), h(i), h(j), g, d, hij)
      if (present(gr)) then
        gr(i) = gr(i) + m(j)*g(1)
        gr(j) = gr(j) - m(i)*g(1)
      end if
      vij = v(:,i) - v(:,j)
      vg = dot_product(vij, g)
      drho(i) = drho(i) + m(j)*vg
      drho(j) = drho(j) + m(i)*vg
      if (present(grad)) call add_pair_gradient(g, vij, m(i), m(j), grad(:,i), grad(:,j))
      heat(i) = heat(i) + m(j)*0.5_rk*visc(k)*vg
      heat(j) = heat(j) + m(i)*0.5_rk*visc(k)*vg
      if (present(r_art)) then
        if (any(r_art(:,i) /= 0.0_rk) .or. any(r_art(:,j) /= 0.0_rk)) then
          ! the work of the pair's artificial stress force, half to each
          work = -0.5_rk*dot_product(vij, art_pair_force(d, hij, spacing, r_art(:,i) + r_art(:,j), g))
          heat(i) = heat(i) + m(j)*work
          heat(j) = heat(j) + m(i)*work
        end if
      end if
    end do
  end subroutine

  !> A pair's terms of the velocity-gradient sums sum_j m_j v_ij (x) grad_i W_ij
  !> (column by column, gi(a + 3(b-1)) for dv_a/dx_b) of particles i and j:
  !> grad_j W_ji = -g and v_ji = -v_ij give j the same product.
  pure subroutine add_pair_gradient(g, vij, mi, mj, gi, gj)
    real(rk), intent(in) :: g(3), vij(3), mi, mj
    real(rk), intent(inout) :: gi(9), gj(9)
    integer :: b
    do b = 1, 3
      gi(3*b-2:3*b) = gi(3*b-2:3*b) + (mj*g(b))*vij
      gj(3*b-2:3*b) = gj(3*b-2:3*b) + (mi*g(b))*vij
    end do
  end subroutine

  !> The hoop stress's force on axisymmetric particles 1..n (after
  !> sph_forces with w and gr): per unit mass
  !>   a_r,i -= sigma_hoop,i gr_i / (rho_i^2 w_i),  sigma_hoop = s(3) - p,
  !> gr_i = sum_j m_j dW_ij/dr the particles' estimate of the area
  !> density's radial gradient, 2 pi rho inside the body: there this is
  !> -sigma_hoop/(rho r), the hoop term of the radial equation of motion.
  !> With gr rather than 2 pi rho it is exactly what the pair sums' own
  !> term p_i/(rho_i^2 w_i) sum_j m_j dW_ij/dr takes off in the radial
  !> direction at a uniform pressure, next to the axis too, where the
  !> mirrored images make gr vanish like r (the plain hoop term would
  !> push the particles there off the axis with p/(rho r)). Its work is
  !> what axisymmetric_rates' hoop rate gives the internal energy.
  pure subroutine hoop_forces(n, w, rho, p, s, gr, acc)
    integer, intent(in) :: n
    real(rk), intent(in) :: w(:), rho(:), p(:), s(:,:), gr(:)
    real(rk), intent(inout) :: acc(:,:)
    integer :: i
    do i = 1, n
      acc(1,i) = acc(1,i) - (s(3,i) - p(i))*gr(i)/(rho(i)**2*w(i))
    end do
  end subroutine

  !> sph_rates' sums of axisymmetric particles 1..n (masses per revolution:
  !> the sums are those of the area density eta = rho w, w = 2 pi r) made
  !> the material's: with the hoop rate d_i = gr_i v_r,i / (rho_i w_i)
  !> (v_r/r inside the body, as hoop_forces takes gr),
  !>   drho_i/dt = sum_j m_j v_ij . grad_i W_ij / w_i - rho_i d_i,
  !>   grad_i    = sum_j m_j v_ij (x) grad_i W_ij / w_i, and its (3,3)
  !>               entry -rho_i d_i (L = -grad/rho: L_33 = d_i, the hoop strain rate),
  !> so that the internal energy gains what hoop_forces and the pair sums
  !> take from the motion.
  pure subroutine axisymmetric_rates(n, w, rho, v, gr, drho, grad)
    integer, intent(in) :: n
    real(rk), intent(in) :: w(:), rho(:), v(:,:), gr(:)
    real(rk), intent(inout) :: drho(:)
    real(rk), intent(inout), optional :: grad(:,:)
    integer :: i
    real(rk) :: hoop
    do i = 1, n
      hoop = gr(i)*v(1,i)/(rho(i)*w(i))
      drho(i) = drho(i)/w(i) - rho(i)*hoop
      if (present(grad)) then
        grad(:,i) = grad(:,i)/w(i)
        grad(9,i) = -rho(i)*hoop
      end if
    end do
  end subroutine

  !> Balsara's (1995) switch of each particle's artificial viscosity,
  !>   f_i = |div v|_i / (|div v|_i + |curl v|_i + 1e-4 c_i/h_i),
  !> 1 in compression without rotation, near 0 in shear: Monaghan's pair
  !> viscosity acts on every approaching pair, so it also resists a shear
  !> flow, in which pairs approach along one diagonal, as if it were a
  !> shock. The velocity gradient is sph_rates' estimate,
  !> L_i = -(1/rho_i) sum_j m_j v_ij (x) grad_i W_ij, at x and v as given
  !> (gs(9,n): work, that sum column by column as sph_rates' grad).
  !> Axisymmetric (w: the radial weights of sph_forces), the in-plane
  !> divergence and curl: the sums over rho w.
  pure subroutine shear_switch(dim, np, pairs, x, v, m, rho, c, h, n, gs, switch, w)
    integer, intent(in) :: dim, np, pairs(:,:), n
    real(rk), intent(in) :: x(:,:), v(:,:), m(:), rho(:), c(:), h(:)
    real(rk), intent(inout) :: gs(:,:)
    real(rk), intent(out) :: switch(:)
    real(rk), intent(in), optional :: w(:)
    real(rk) :: g(3), d, hij, dv, curl(3)
    integer :: k, i, j
    gs(:,1:n) = 0
    do k = 1, np
      i = pairs(1,k)
      j = pairs(2,k)
      call pair_gradient(dim, x(:,i), x(:,j), h(i), h(j), g, d, hij)
      call add_pair_gradient(g, v(:,i) - v(:,j), m(i), m(j), gs(:,i), gs(:,j))
    end do
    do i = 1, n
      if (present(w)) gs(:,i) = gs(:,i)/w(i)
      ! L = -gs/rho (gs(a + 3(b-1)) for dv_a/dx_b): |div v| and |curl v| need no sign
      dv = abs(gs(1,i) + gs(5,i) + gs(9,i))/rho(i)
      curl = [gs(6,i) - gs(8,i), gs(7,i) - gs(3,i), gs(2,i) - gs(4,i)]/rho(i)
      switch(i) = dv/(dv + norm2(curl) + 1e-4_rk*c(i)/h(i))
    end do
  end subroutine

  !> A pair's artificial stress force per unit mass of the other particle,
  !> (W(d)/W(dp))^n (R_i + R_j) grad_i W_ij, with rsum = R_i + R_j (6, as s)
  !> and dp = spacing h_ij, the particles' initial spacing (Monaghan 2000;
  !> Gray, Monaghan and Swift 2001).
  pure function art_pair_force(d, hij, spacing, rsum, g) result(f)
    real(rk), intent(in) :: d, hij, spacing, rsum(6), g(3)
    real(rk) :: f(3), fn
    ! (W(d)/W(dp) is the kernel shape's ratio: the factor sigma/h^dim cancels)
    fn = (spline_shape(d/hij)/spline_shape(spacing))**art_exponent
    f = fn*[rsum(1)*g(1) + rsum(4)*g(2) + rsum(6)*g(3), rsum(4)*g(1) + rsum(2)*g(2) + rsum(5)*g(3), &
            rsum(6)*g(1) + rsum(5)*g(2) + rsum(3)*g(3)]
  end function

  !> The artificial stress R (6, as s) of n particles (Monaghan 2000; Gray,
  !> Monaghan and Swift 2001): in the principal axes of the stress
  !> sigma = s - p I, R_a = -eps sigma_a / rho^2 for each principal stress
  !> in tension (sigma_a > 0), 0 otherwise; rotated back. The pair term
  !> (W_ij/W(dp))^n (R_i + R_j) of the momentum equation then pushes apart
  !> particles in tension that come closer than their spacing: SPH's
  !> tensile instability (Swegle, Hicks and Attaway 1995; particles in
  !> tension clump instead of parting).
  pure subroutine artificial_stress(n, eps, rho, p, s, r)
    integer, intent(in) :: n
    real(rk), intent(in) :: eps(:), rho(:), p(:), s(:,:)
    real(rk), intent(out) :: r(:,:)
    integer :: i, a, b
    real(rk) :: sig(3,3), q(3,3), lam(3), ra(3,3)
    do i = 1, n
      r(:,i) = 0
      if (eps(i) == 0.0_rk) cycle
      sig = reshape([s(1,i) - p(i), s(4,i), s(6,i), s(4,i), s(2,i) - p(i), s(5,i), s(6,i), s(5,i), s(3,i) - p(i)], [3, 3])
      call symmetric_eigen3(sig, lam, q)
      if (all(lam <= 0.0_rk)) cycle
      ra = 0
      do a = 1, 3
        if (lam(a) <= 0.0_rk) cycle
        do b = 1, 3
          ra(:,b) = ra(:,b) - (eps(i)*lam(a)/rho(i)**2)*q(:,a)*q(b,a)
        end do
      end do
      r(:,i) = [ra(1,1), ra(2,2), ra(3,3), ra(1,2), ra(2,3), ra(3,1)]
    end do
  end subroutine

  !> Eigenvalues lam and eigenvectors (the columns of q) of a symmetric 3x3
  !> matrix a, by cyclic Jacobi rotations until the off-diagonal part is
  !> at the rounding of a.
  pure subroutine symmetric_eigen3(a, lam, q)
    real(rk), intent(in) :: a(3,3)
    real(rk), intent(out) :: lam(3), q(3,3)
    integer, parameter :: pp(3) = [1, 1, 2], qq(3) = [2, 3, 3]
    real(rk) :: b(3,3), theta, t, sn, tau, bpq, scale, g, hh
    integer :: sweep, r, ip, iq, k
    b = a
    q = 0
    do r = 1, 3
      q(r,r) = 1
    end do
    scale = max(maxval(abs(a)), tiny(1.0_rk))
    do sweep = 1, 50
      if (abs(b(1,2)) + abs(b(1,3)) + abs(b(2,3)) <= 1e-15_rk*scale) exit
      do r = 1, 3
        ip = pp(r); iq = qq(r)
        bpq = b(ip,iq)
        if (bpq == 0.0_rk) cycle
        ! the rotation in the plane (ip, iq) that zeroes b(ip,iq) (Numerical Recipes' jacobi)
        theta = (b(iq,iq) - b(ip,ip))/(2.0_rk*bpq)
        t = sign(1.0_rk, theta)/(abs(theta) + sqrt(theta**2 + 1.0_rk))
        sn = t/sqrt(t**2 + 1.0_rk)
        tau = sn/(1.0_rk + 1.0_rk/sqrt(t**2 + 1.0_rk))
        b(ip,ip) = b(ip,ip) - t*bpq
        b(iq,iq) = b(iq,iq) + t*bpq
        b(ip,iq) = 0; b(iq,ip) = 0
        do k = 1, 3
          if (k == ip .or. k == iq) cycle
          g = b(k,ip); hh = b(k,iq)
          b(k,ip) = g - sn*(hh + g*tau); b(ip,k) = b(k,ip)
          b(k,iq) = hh + sn*(g - hh*tau); b(iq,k) = b(k,iq)
        end do
        do k = 1, 3
          g = q(k,ip); hh = q(k,iq)
          q(k,ip) = g - sn*(hh + g*tau)
          q(k,iq) = hh + sn*(g - hh*tau)
        end do
      end do
    end do
    lam = [b(1,1), b(2,2), b(3,3)]
  end subroutine

  !> The particles' density and energy over a step dt from their rates
  !> (sph_rates): rho(n+1) = rho(n) exp(dt drho/rho(n)) (the exact
  !> solution at a constant rate of dilatation: never negative), then the
  !> energy equation with the EOS solved exactly as the elements do
  !> (volumetric_update: de = heat dt - (p(n) + p(n+1))/2 d(1/rho), no
  !> element viscosity; tension only where strong), and the sound speed.
  !> p, c in: of step n; out: of step n+1; temp: the temperature of the
  !> particles' shear modulus (the wave speed). A strengthless particle without
  !> pressure at both ends of the step keeps its density if it would fall:
  !> failed material does not expand in tension, it parts (no pressure: the
  !> volume change would do no work either way); without this, particles
  !> that fly apart thin out and must then be squeezed back to their
  !> density before they push.
  pure subroutine particle_update(mat, n, dt, m, drho, heat, strong, temp, rho, e, p, c)
    type(material_cfg_t), intent(in) :: mat
    integer, intent(in) :: n
    real(rk), intent(in) :: dt, m(:), drho(:), heat(:), temp(:)
    logical, intent(in) :: strong(:)
    real(rk), intent(inout) :: rho(:), e(:), p(:), c(:)
    real(rk), dimension(block_size) :: vol, zero, j_old, j_new, w_visc, q, bulk_tan, stiff, pp, rho_old
    logical :: no_tension(block_size)
    integer :: first, nb, i, k
    zero = 0
    do first = 1, n, block_size
      nb = min(block_size, n - first + 1)
      no_tension(1:nb) = .not. strong(first:first+nb-1)
      do i = 1, nb
        k = first + i - 1
        j_old(i) = mat%rho0/rho(k)
        rho_old(i) = rho(k)
        rho(k) = rho(k)*exp(dt*drho(k)/rho(k))
        j_new(i) = mat%rho0/rho(k)
        vol(i) = m(k)/rho(k)
        ! heat dt per unit mass, as work per unit volume for volumetric_update
        w_visc(i) = heat(k)*dt*rho(k)
      end do
      pp(1:nb) = p(first:first+nb-1)
      call volumetric_update(mat, 0.0_rk, 0.0_rk, nb, dt, vol(1:nb), zero(1:nb), zero(1:nb), m(first:first+nb-1), &
                             j_old(1:nb), j_new(1:nb), w_visc(1:nb), no_tension(1:nb), e(first:first+nb-1), pp(1:nb), &
                             q(1:nb), bulk_tan(1:nb), stiff(1:nb))
      do i = 1, nb
        k = first + i - 1
        if (no_tension(i) .and. p(k) == 0.0_rk .and. pp(i) == 0.0_rk) rho(k) = max(rho(k), rho_old(i))
        call particle_pressure(mat, rho(k), e(k), strong(k), p(k), c(k))
        c(k) = wave_speed(mat, strong(k), rho(k), c(k), p(k), temp(k))
      end do
    end do
  end subroutine

  !> The speed of the fastest wave in a particle of density rho whose
  !> bulk sound speed is c_bulk: c_bulk, or with its strength the
  !> longitudinal wave's sqrt(c_bulk^2 + 4 G / (3 rho)), which the step
  !> must follow; G at its pressure p and temperature temp where the
  !> material's shear modulus depends on them.
  pure elemental real(rk) function wave_speed(mat, strong, rho, c_bulk, p, temp) result(c)
    type(material_cfg_t), intent(in) :: mat
    logical, intent(in) :: strong
    real(rk), intent(in) :: rho, c_bulk, p, temp
    real(rk) :: g
    c = c_bulk
    if (.not. strong) return
    g = mat%shear_modulus
    ! the modulus of the particle's state, as its strength takes it
    if (mat%shear_model /= shear_constant) g = shear_modulus_at(mat, p, temp, rho/mat%rho0)
    c = sqrt(c_bulk**2 + 4.0_rk*g/(3.0_rk*rho))
  end function

  !> The deviatoric stress s(6,:) of particles 1..n of material mat over
  !> dt, for those that keep their strength (strong: made from an element
  !> that had not fractured, and not fractured since; the others keep
  !> s = 0): the velocity gradient L = -grad/rho (sph_rates; rho of step n)
  !> gives the strain rate and spin that the elements' strength_block takes
  !> (Jaumann rotation, hypoelastic trial step, radial return); plastic
  !> work heats (Taylor-Quinney) and softens as in an element; the
  !> material's fracture criterion (fracture_update, at the pressure p of
  !> step n: a strong particle carries tension, so it spalls at p_spall as
  !> an element does) makes the particle strengthless for good. heat
  !> (J/(kg s)) is raised by the deviatoric work of the step, s_mid : D /
  !> rho, which particle_update books with the pressure's.
  pure subroutine particle_strength(mat, n, dt, rho, grad, p, strong, s, eps_p, hard, soft, temp, damage, heat)
    type(material_cfg_t), intent(in) :: mat
    integer, intent(in) :: n
    real(rk), intent(in) :: dt, rho(:), grad(:,:), p(:)
    logical, intent(inout) :: strong(:)
    real(rk), intent(inout) :: s(:,:), eps_p(:), hard(:), soft(:), temp(:), damage(:), heat(:)
    real(rk), dimension(block_size, 6) :: d, sb
    real(rk), dimension(block_size, 3) :: w
    real(rk), dimension(block_size) :: w_dev, w_pl, sf, hd, ep, ep0, eta
    real(rk) :: l(3,3), t_old
    integer :: first, nb, i, k
    logical :: fractured
    if (dt <= 0.0_rk) return
    do first = 1, n, block_size
      nb = min(block_size, n - first + 1)
      if (.not. any(strong(first:first+nb-1))) cycle
      do i = 1, nb
        k = first + i - 1
        l = reshape(-grad(:,k)/rho(k), [3, 3])
        d(i,:) = [l(1,1), l(2,2), l(3,3), 0.5_rk*(l(1,2) + l(2,1)), 0.5_rk*(l(2,3) + l(3,2)), 0.5_rk*(l(3,1) + l(1,3))]
        w(i,:) = [0.5_rk*(l(1,2) - l(2,1)), 0.5_rk*(l(2,3) - l(3,2)), 0.5_rk*(l(3,1) - l(1,3))]
        sb(i,:) = s(:,k)
        sf(i) = soft(k)
        hd(i) = hard(k)
        ep(i) = eps_p(k)
        ep0(i) = ep(i)
        eta(i) = rho(k)/mat%rho0
      end do
      call strength_block(mat, block_size, nb, dt, d, w, sf(1:nb), temp(first:first+nb-1), p(first:first+nb-1), &
                          eta(1:nb), hd(1:nb), sb, ep(1:nb), w_dev(1:nb), w_pl(1:nb))
      do i = 1, nb
        k = first + i - 1
        if (.not. strong(k)) cycle
        s(:,k) = sb(i,:)
        hard(k) = hd(i)
        eps_p(k) = ep(i)
        heat(k) = heat(k) + w_dev(i)/(rho(k)*dt)
        if (w_pl(i) > 0.0_rk .and. mat%specific_heat > 0.0_rk) then
          t_old = temp(k)
          temp(k) = t_old + mat%taylor_quinney*w_pl(i)/(rho(k)*mat%specific_heat)
          soft(k) = thermal_softening_update(mat, sf(i), t_old, temp(k))
        end if
        if (fracture_enabled(mat)) then
          call fracture_update(mat, dt, ep(i) - ep0(i), ep(i), von_mises(sb(i,:)), p(k), temp(k), damage(k), fractured)
          if (fractured) then
            strong(k) = .false.
            s(:,k) = 0.0_rk
          end if
        end if
      end do
    end do
  end subroutine

  !> grad_i W_ij = dW/dr(|x_ij|, h_ij) x_ij/|x_ij| (= - grad_j W_ij), the
  !> distance d and h_ij; g = 0 for coincident particles and beyond 2 h_ij.
  pure subroutine pair_gradient(dim, xi, xj, hi, hj, g, d, hij)
    integer, intent(in) :: dim
    real(rk), intent(in) :: xi(3), xj(3), hi, hj
    real(rk), intent(out) :: g(3), d, hij
    hij = 0.5_rk*(hi + hj)
    d = norm2(xi - xj)
    g = 0
    if (d > 0.0_rk .and. d < 2.0_rk*hij) g = (spline_dw(d, hij, dim)/d)*(xi - xj)
  end subroutine

  !> The particles' stable step: courant times the smallest h_i over the
  !> particle's signal speed (vsig from sph_rates, at least its own c);
  !> huge() without particles.
  pure real(rk) function sph_stable_dt(n, courant, h, c, vsig) result(dt)
    integer, intent(in) :: n
    real(rk), intent(in) :: courant, h(:), c(:), vsig(:)
    integer :: i
    dt = huge(1.0_rk)
    do i = 1, n
      dt = min(dt, courant*h(i)/max(vsig(i), c(i), tiny(1.0_rk)))
    end do
  end function

  !> The pairs of n particles within 2 h_ij of each other, every pair once
  !> as (i, j) with i < j, in ascending (i, j): a grid of cells of side
  !> 2 max h over the particles' box, each particle tested against the
  !> particles of its own and the 26 (2D: 8) cells around it. Work arrays
  !> (the caller keeps them between calls): cell_start(ncell_max+1),
  !> order(n), cand(max(n, ncell_max)) (each cell's fill pointer, then each
  !> particle's neighbours); np returns the pair count, and -1 when pairs(2,:) is too
  !> small (call again with room for more).
  pure subroutine sph_pairs(dim, n, x, h, ncell_max, cell_start, order, cand, pairs, np)
    integer, intent(in) :: dim, n, ncell_max
    real(rk), intent(in) :: x(:,:), h(:)
    integer, intent(inout) :: cell_start(:), order(:), cand(:)
    integer, intent(out) :: pairs(:,:), np
    real(rk) :: lo(3), side, hij
    integer :: nc(3), i, j, k, a, b, cz, cell, ci(3), nn, lo_c(3), hi_c(3), ncell
    np = 0
    if (n < 2) return
    lo = minval(x(:,1:n), dim=2)
    side = 2.0_rk*maxval(h(1:n))
    nc = 1
    do a = 1, dim
      nc(a) = max(1, min(int((maxval(x(a,1:n)) - lo(a))/side) + 1, int(real(ncell_max, rk)**(1.0_rk/dim))))
    end do
    ! a box wider than the cells can cover: larger cells (the pairs are the same)
    side = max(side, maxval((maxval(x(1:dim,1:n), dim=2) - lo(1:dim))/nc(1:dim)))
    ncell = product(nc)
    ! counting sort of the particles by cell, stable (ascending i in a cell)
    cell_start(1:ncell+1) = 0
    do i = 1, n
      cell = cell_of(x(:,i))
      cell_start(cell+1) = cell_start(cell+1) + 1
    end do
    cell_start(1) = 1
    do cell = 1, ncell
      cell_start(cell+1) = cell_start(cell+1) + cell_start(cell)
    end do
    ! cand as each cell's fill pointer
    cand(1:ncell) = cell_start(1:ncell)
    do i = 1, n
      cell = cell_of(x(:,i))
      order(cand(cell)) = i
      cand(cell) = cand(cell) + 1
    end do
    do i = 1, n
      ci = cell_index(x(:,i))
      ! nc(3) = 1 in 2D: one layer
      lo_c = max(ci - 1, 0)
      hi_c = min(ci + 1, nc - 1)
      nn = 0
      do cz = lo_c(3), hi_c(3)
        do b = lo_c(2), hi_c(2)
          do a = lo_c(1), hi_c(1)
            cell = 1 + a + nc(1)*(b + nc(2)*cz)
            do k = cell_start(cell), cell_start(cell+1) - 1
              j = order(k)
              if (j <= i) cycle
              hij = 0.5_rk*(h(i) + h(j))
              ! (2D: z = 0 for all, the third term 0)
              if ((x(1,i) - x(1,j))**2 + (x(2,i) - x(2,j))**2 + (x(3,i) - x(3,j))**2 >= (2.0_rk*hij)**2) cycle
              nn = nn + 1
              cand(nn) = j
            end do
          end do
        end do
      end do
      call sort_ints(cand(1:nn))
      if (np + nn > size(pairs, 2)) then
        np = -1
        return
      end if
      do k = 1, nn
        pairs(:, np + k) = [i, cand(k)]
      end do
      np = np + nn
    end do
  contains
    pure function cell_index(y) result(cidx)
      real(rk), intent(in) :: y(3)
      integer :: cidx(3)
      cidx = 0
      cidx(1:dim) = min(int((y(1:dim) - lo(1:dim))/side), nc(1:dim) - 1)
    end function
    pure integer function cell_of(y)
      real(rk), intent(in) :: y(3)
      integer :: cidx(3)
      cidx = cell_index(y)
      cell_of = 1 + cidx(1) + nc(1)*(cidx(2) + nc(2)*cidx(3))
    end function
  end subroutine

  !> An element of nc corners becomes a particle: the corners' mass shares
  !> m_a (what the element lumped onto its nodes, which they lose) make its
  !> mass, their momentum its momentum (v = sum m_a v_a / m, at the centre
  !> of mass x = sum m_a x_a / m); the kinetic energy the corners' relative
  !> motion had, sum m_a |v_a - v|^2 / 2 >= 0, is added to the internal
  !> energy, so mass, momentum and energy are exact through the conversion
  !> (the element's rotation about its centre is not: that energy is heat
  !> now). e_elem: the element's specific internal energy (J/kg); rho its
  !> density. e, ke_to_heat: the particle's specific internal energy and the
  !> kinetic energy made heat (J).
  pure subroutine element_to_particle(nc, m_a, x_a, v_a, e_elem, m, x, v, e, ke_to_heat)
    integer, intent(in) :: nc
    real(rk), intent(in) :: m_a(:), x_a(:,:), v_a(:,:), e_elem
    real(rk), intent(out) :: m, x(3), v(3), e, ke_to_heat
    integer :: a
    m = sum(m_a(1:nc))
    x = 0
    v = 0
    do a = 1, nc
      x = x + m_a(a)*x_a(:,a)
      v = v + m_a(a)*v_a(:,a)
    end do
    x = x/m
    v = v/m
    ke_to_heat = 0
    do a = 1, nc
      ke_to_heat = ke_to_heat + 0.5_rk*m_a(a)*sum((v_a(:,a) - v)**2)
    end do
    e = e_elem + ke_to_heat/m
  end subroutine
end module udar_sph
