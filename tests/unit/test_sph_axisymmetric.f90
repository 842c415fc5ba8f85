!> Unit tests of the axisymmetric particles (udar_sph with radial weights,
!> hoop_forces, axisymmetric_rates; theory.md section 15 "Axisymmetric"):
!> on a lattice of rings (spacing a, the first ring at a/2 from the axis,
!> masses per revolution rho0 a^2 2 pi r, their images across the axis
!> made here as the driver makes them):
!> - at a uniform pressure every ring is at rest, the one next to the
!>   axis too (the hoop term with the pair sums' own radial gradient);
!>   the plain hoop term p/(rho r) would push that ring off the axis
!>   (shown: the check computes it);
!> - under a uniform radial expansion v_r = eps r the continuity gives
!>   drho/dt = -2 eps rho0 and the strain rates d_rr = d_hoop = eps, d_zz =
!>   0 (the continuum's; within 2 % inside the body), and next to the axis
!>   the divergence is measured;
!> - a rigid translation along the axis gives no rate at all (exact);
!> On a random cloud of rings off the axis with random pressures and
!> deviators, the forces' power is exactly what the rates give the internal
!> energy (the hoop stress's work included) and the momentum along the
!> axis is exact.
program test_sph_axisymmetric
  use udar_kinds, only: rk, pi
  use udar_strings, only: r2s, itoa
  use udar_sph, only: sph_forces, sph_rates, sph_pairs, smoothing_length, hoop_forces, axisymmetric_rates
  use unit_checks, only: check, check_summary
  implicit none
  integer, parameter :: nr = 8, nz = 13, n = nr*nz, max_pairs = 40000
  real(rk), parameter :: a = 1e-4_rk, rho0 = 7850.0_rk, p0 = 1e9_rk

  call lattice_tests()
  call cloud_tests(.false.)
  call cloud_tests(.true.)
  call check_summary()

contains

  !> The rings' lattice and its images: n rings, then n images at -r.
  subroutine ring_lattice(x, m, rho, hh, w)
    real(rk), intent(out) :: x(:,:), m(:), rho(:), hh(:), w(:)
    integer :: i, j, q
    q = 0
    do j = 1, nz
      do i = 1, nr
        q = q + 1
        x(:,q) = [(i - 0.5_rk)*a, (j - (nz + 1)/2)*a, 0.0_rk]
      end do
    end do
    x(:,n+1:2*n) = x(:,1:n)
    x(1,n+1:2*n) = -x(1,1:n)
    m(1:n) = rho0*a**2*2.0_rk*pi*x(1,1:n)
    m(n+1:2*n) = m(1:n)
    rho = rho0
    w = 2.0_rk*pi*abs(x(1,:))
    ! the driver's: of the area m / (rho 2 pi r)
    hh = smoothing_length(m/w, rho, 1.2_rk, 2)
  end subroutine

  !> The pairs of the first n_all points, n_real particles then their
  !> images, without those of two images (the driver's rule).
  subroutine pairs_with_images(n_real, n_all, x, hh, pairs, np)
    integer, intent(in) :: n_real, n_all
    real(rk), intent(in) :: x(:,:), hh(:)
    integer, intent(out) :: pairs(:,:), np
    integer :: cell_start(8193), order(n_all), cand(n_all + 8192), k, nt
    call sph_pairs(2, n_all, x, hh, 8192, cell_start, order, cand, pairs, np)
    nt = 0
    do k = 1, np
      if (pairs(1,k) > n_real) cycle
      nt = nt + 1
      pairs(:,nt) = pairs(:,k)
    end do
    np = nt
  end subroutine

  subroutine lattice_tests()
    real(rk) :: x(3,2*n), v(3,2*n), m(2*n), rho(2*n), p(2*n), c(2*n), hh(2*n), w(2*n), s(6,2*n), acc(3,2*n), &
                vsig(2*n), gr(2*n), drho(2*n), dedt(2*n), grad(9,2*n), l(3,3), naive, eps, worst, u
    real(rk), allocatable :: coef(:)
    integer, allocatable :: pairs(:,:)
    integer :: np, axis_ring, inner, k, j
    allocate(pairs(2,max_pairs), coef(max_pairs))
    call ring_lattice(x, m, rho, hh, w)
    call check('smoothing_length_of_the_area', abs(hh(1)/(1.2_rk*a) - 1.0_rk) < 1e-14_rk, 'h/a '//r2s(hh(1)/a))
    call pairs_with_images(n, 2*n, x, hh, pairs, np)
    ! the ring next to the axis and one inside, both on the middle row
    axis_ring = nr*((nz - 1)/2) + 1
    inner = axis_ring + 3
    p = p0
    c = 4570.0_rk
    s = 0
    v = 0
    ! ---- uniform pressure: at rest
    acc = 0
    vsig = 0
    gr = 0
    call sph_forces(2, 0.0_rk, 0.0_rk, np, pairs, x, v, m, rho, p, c, hh, s, coef, acc, vsig, w=w, gr=gr)
    ! (what the plain hoop term p/(rho r) would leave the ring at the axis)
    naive = acc(1,axis_ring) + p0/(rho0*x(1,axis_ring))
    call hoop_forces(n, w, rho, p, s, gr, acc)
    print '(a)', 'MEASURED uniform pressure: |a| at the axis ring '//r2s(norm2(acc(:,axis_ring)))//' m/s2, inside '// &
                 r2s(norm2(acc(:,inner)))//'; the plain hoop term would give '//r2s(naive)//' m/s2 (p/(rho r) = '// &
                 r2s(p0/(rho0*x(1,axis_ring)))//'); gr/(2 pi rho0) '//r2s(gr(axis_ring)/(2*pi*rho0))//' at the axis, '// &
                 r2s(gr(inner)/(2*pi*rho0))//' inside'
    call check('uniform_pressure_axis_ring_at_rest', norm2(acc(:,axis_ring)) < 1e-9_rk*p0/(rho0*x(1,axis_ring)), &
               '|a| '//r2s(norm2(acc(:,axis_ring)))//' m/s2')
    call check('uniform_pressure_inner_ring_at_rest', norm2(acc(:,inner)) < 1e-9_rk*p0/(rho0*x(1,inner)), &
               '|a| '//r2s(norm2(acc(:,inner)))//' m/s2')
    call check('plain_hoop_term_pushes_the_axis_ring', naive > 0.1_rk*p0/(rho0*x(1,axis_ring)), &
               'a_r '//r2s(naive)//' m/s2')
    call check('radial_gradient_inside_is_2_pi_rho', abs(gr(inner)/(2*pi*rho0) - 1.0_rk) < 0.02_rk, &
               'gr/(2 pi rho0) '//r2s(gr(inner)/(2*pi*rho0)))
    ! ---- uniform radial expansion v_r = eps r (the images' v_r mirrored: -eps |r|, i.e. eps x)
    eps = 1e3_rk
    v = 0
    v(1,:) = eps*x(1,:)
    call lattice_rates(np, pairs, x, v, m, hh, w, rho, drho, dedt, grad, gr)
    l = reshape(-grad(:,inner)/rho0, [3, 3])
    print '(a)', 'MEASURED radial expansion eps r: inside drho/dt '//r2s(drho(inner))//' against -2 eps rho0 = '// &
                 r2s(-2*eps*rho0)//', L_rr '//r2s(l(1,1))//', L_zz '//r2s(l(2,2))//', hoop '//r2s(l(3,3))// &
                 ' 1/s (eps '//r2s(eps)//'); at the axis ring drho/dt / (-2 eps rho0) '//r2s(drho(axis_ring)/(-2*eps*rho0))
    call check('radial_expansion_continuity', abs(drho(inner)/(-2*eps*rho0) - 1.0_rk) < 0.02_rk, &
               'ratio '//r2s(drho(inner)/(-2*eps*rho0)))
    call check('radial_expansion_strain_rates', abs(l(1,1) - eps) < 0.02_rk*eps .and. abs(l(3,3) - eps) < 0.02_rk*eps &
               .and. abs(l(2,2)) < 1e-9_rk*eps, 'L_rr '//r2s(l(1,1))//' hoop '//r2s(l(3,3))//' L_zz '//r2s(l(2,2)))
    ! next to the axis the sums' images of the area density 2 pi rho |r| have a kink: measured, and held
    print '(a)', 'MEASURED radial expansion, drho/dt / (-2 eps rho0) on the middle row, rings 1-4 from the axis: '// &
                 r2s(drho(axis_ring)/(-2*eps*rho0))//' '//r2s(drho(axis_ring+1)/(-2*eps*rho0))//' '// &
                 r2s(drho(axis_ring+2)/(-2*eps*rho0))//' '//r2s(drho(axis_ring+3)/(-2*eps*rho0))
    call check('radial_expansion_second_ring', abs(drho(axis_ring+1)/(-2*eps*rho0) - 1.0_rk) < 0.05_rk, &
               'ratio '//r2s(drho(axis_ring+1)/(-2*eps*rho0)))
    call check('radial_expansion_axis_ring_bounded', abs(drho(axis_ring)/(-2*eps*rho0) - 1.0_rk) < 0.4_rk, &
               'ratio '//r2s(drho(axis_ring)/(-2*eps*rho0)))
    ! ---- a rigid translation along the axis: nothing
    v = 0
    v(2,:) = 250.0_rk
    call lattice_rates(np, pairs, x, v, m, hh, w, rho, drho, dedt, grad, gr)
    call check('axial_translation_no_rates', all(drho(1:n) == 0.0_rk) .and. all(grad(:,1:n) == 0.0_rk) .and. &
               all(dedt(1:n) == 0.0_rk), 'largest |drho| '//r2s(maxval(abs(drho(1:n)))))
    ! ---- an axial translation with a small random radial motion: the rates on the axis ring stay finite
    worst = 0
    do k = 1, n
      call random_number(u)
      v(1,k) = 10.0_rk*(u - 0.5_rk)*x(1,k)/(nr*a)
    end do
    v(1,n+1:2*n) = -v(1,1:n)
    call lattice_rates(np, pairs, x, v, m, hh, w, rho, drho, dedt, grad, gr)
    do j = 1, n
      worst = max(worst, abs(drho(j))/rho0)
    end do
    call check('rates_finite_at_the_axis', worst < 1e6_rk, 'largest |drho/dt|/rho0 '//r2s(worst)//' 1/s')
  end subroutine

  !> The lattice's rates at v (images included, no viscosity), made axisymmetric.
  subroutine lattice_rates(np, pairs, x, v, m, hh, w, rho, drho, dedt, grad, gr)
    integer, intent(in) :: np, pairs(:,:)
    real(rk), intent(in) :: x(:,:), v(:,:), m(:), hh(:), w(:), rho(:)
    real(rk), intent(out) :: drho(:), dedt(:), grad(:,:), gr(:)
    real(rk) :: no_visc(np)
    no_visc = 0
    drho = 0
    dedt = 0
    grad = 0
    gr = 0
    call sph_rates(2, 0.0_rk, np, pairs, x, v, m, hh, no_visc, drho, dedt, grad, gr=gr)
    call axisymmetric_rates(n, w, rho, v, gr, drho, grad)
  end subroutine

  !> A random cloud of rings: energy and axial momentum; at_axis: the
  !> cloud reaches the axis and takes its images (the half system's
  !> energy: the particles' own, the images moving as their originals).
  subroutine cloud_tests(at_axis)
    logical, intent(in) :: at_axis
    integer, parameter :: nr = 90, nc = 2*nr
    real(rk) :: x(3,nc), v(3,nc), m(nc), rho(nc), p(nc), c(nc), hh(nc), w(nc), s(6,nc), acc(3,nc), vsig(nc), gr(nc), &
                drho(nc), dedt(nc), grad(9,nc), u(3), l(3,3), power, scale_e, mom, scale_f, gr_rates(nc)
    real(rk), allocatable :: coef(:)
    integer, allocatable :: pairs(:,:)
    integer :: i, np, nt
    character(len=:), allocatable :: tag
    allocate(pairs(2,max_pairs), coef(max_pairs))
    tag = trim(merge('_with_images', '            ', at_axis))
    call random_seed(put=[(4242 + 3*i, i = 1, 64)])
    do i = 1, nr
      call random_number(u)
      x(:,i) = [merge(1e-5_rk, 3e-3_rk, at_axis) + 3e-3_rk*u(1), 3e-3_rk*u(2), 0.0_rk]
      call random_number(u)
      v(:,i) = [200.0_rk*(u(1) - 0.5_rk), 200.0_rk*(u(2) - 0.5_rk), 0.0_rk]
      rho(i) = rho0*(1.0_rk + 0.1_rk*u(3))
      m(i) = rho(i)*(2.5e-4_rk)**2*2.0_rk*pi*x(1,i)*(1.0_rk + 0.3_rk*u(1))
      call random_number(u)
      p(i) = p0*u(1)
      c(i) = 4570.0_rk
      hh(i) = 3e-4_rk*(1.0_rk + 0.5_rk*u(2))
      call random_number(u)
      ! a deviator: rr, zz, hoop (traceless), rz
      s(:,i) = 1e8_rk*[u(1) - 0.5_rk, u(2) - 0.5_rk, 0.0_rk, u(3) - 0.5_rk, 0.0_rk, 0.0_rk]
      s(3,i) = -s(1,i) - s(2,i)
    end do
    nt = nr
    if (at_axis) then
      ! the images across the axis, as the driver makes them
      nt = nc
      x(:,nr+1:nc) = x(:,1:nr); x(1,nr+1:nc) = -x(1,1:nr)
      v(:,nr+1:nc) = v(:,1:nr); v(1,nr+1:nc) = -v(1,1:nr)
      s(:,nr+1:nc) = s(:,1:nr); s(4,nr+1:nc) = -s(4,1:nr)
      m(nr+1:nc) = m(1:nr); rho(nr+1:nc) = rho(1:nr); p(nr+1:nc) = p(1:nr); c(nr+1:nc) = c(1:nr)
      hh(nr+1:nc) = hh(1:nr)
    end if
    w(1:nt) = 2.0_rk*pi*abs(x(1,1:nt))
    call pairs_with_images(nr, nt, x, hh, pairs, np)
    acc = 0
    vsig = 0
    gr = 0
    call sph_forces(2, 1.0_rk, 2.0_rk, np, pairs, x, v, m, rho, p, c, hh, s, coef, acc, vsig, w=w, gr=gr)
    call hoop_forces(nr, w, rho, p, s, gr, acc)
    drho = 0
    dedt = 0
    grad = 0
    gr_rates = 0
    call sph_rates(2, 0.0_rk, np, pairs, x, v, m, hh, coef, drho, dedt, grad, gr=gr_rates)
    call check('rates_take_the_forces_radial_sums'//tag, maxval(abs(gr_rates(1:nr) - gr(1:nr))) <= &
               1e-12_rk*maxval(abs(gr(1:nr))), 'largest difference '//r2s(maxval(abs(gr_rates(1:nr) - gr(1:nr)))))
    call axisymmetric_rates(nr, w, rho, v, gr_rates, drho, grad)
    power = 0
    scale_e = 0
    mom = 0
    scale_f = 0
    do i = 1, nr
      l = reshape(-grad(:,i)/rho(i), [3, 3])
      ! de/dt = p/rho^2 drho/dt + heat + s : L / rho (s symmetric: its rz pairs with both L_rz and L_zr)
      dedt(i) = dedt(i) + p(i)/rho(i)**2*drho(i) + (s(1,i)*l(1,1) + s(2,i)*l(2,2) + s(3,i)*l(3,3) + &
                                                    s(4,i)*(l(1,2) + l(2,1)))/rho(i)
      power = power + m(i)*(dot_product(v(:,i), acc(:,i)) + dedt(i))
      scale_e = scale_e + m(i)*(abs(dot_product(v(:,i), acc(:,i))) + abs(dedt(i)))
      mom = mom + m(i)*acc(2,i)
      scale_f = scale_f + m(i)*abs(acc(2,i))
    end do
    call check('axisymmetric_energy_exact'//tag, abs(power) < 1e-13_rk*scale_e, 'power '//r2s(power/scale_e)//' of its scale')
    call check('axisymmetric_axial_momentum_exact'//tag, abs(mom) < 1e-14_rk*scale_f, 'sum m a_z '//r2s(mom/scale_f))
    print '(a)', 'MEASURED random cloud of '//itoa(nr)//' rings'//tag//', '//itoa(np)//' pairs: power '//r2s(power/scale_e)// &
                 ' and axial force '//r2s(mom/scale_f)//' of their scales'
  end subroutine
end program test_sph_axisymmetric
