!> Unit test of the particles' symmetry planes (udar_particle_driver,
!> issue 15): a cloud of particles symmetric about the planes x = 0 and
!> y = 0 (a full model) against its quarter with the two planes as
!> symmetry walls (mirror images made by the driver). The quarter's
!> particles must get the full model's accelerations, density rates and
!> heating to round-off, including the particles near the planes' common
!> line (three images each); without the images the quarter's particles
!> next to a plane feel nothing from across it (shown failing: the test
!> below with no planes). The same for particles that keep their strength,
!> in tension with a deviator, so that the artificial stress acts (its
!> images' R from the mirrored stress). Both with Balsara's switch on the
!> viscosity (an image takes its original's factor).
program test_particle_ghosts
  use udar_kinds, only: rk
  use udar_strings, only: r2s, itoa
  use udar_config, only: material_cfg_t, eos_linear, eroded_particles
  use udar_domain, only: domain_t, wall_t
  use udar_particle_model, only: particles_t, particles_reserve
  use udar_particle_driver, only: particles_forces, particles_move, particles_finish_step
  use unit_checks, only: check, check_summary
  implicit none
  integer, parameter :: nq = 60
  type(particles_t) :: quarter, full, lone, sparse, tq, tf
  type(domain_t) :: dom_q, dom_f, dom_n
  real(rk) :: u(3), xq(3,nq), vq(3,nq), err_a, err_r, err_h, scale_a, scale_r, scale_h, dt, sq(6,nq)
  integer :: i, k

  call random_seed(put=[(4711 + 13*i, i = 1, 64)])
  do i = 1, nq
    call random_number(u)
    xq(:,i) = [1.5e-3_rk*u(1), 1.5e-3_rk*u(2), 3e-3_rk*u(3)]
    call random_number(u)
    vq(:,i) = 300.0_rk*(u - 0.5_rk)
  end do
  call material(dom_q)
  call material(dom_f)
  call material(dom_n)
  allocate(dom_q%sym_walls(2), dom_f%sym_walls(0), dom_n%sym_walls(0))
  dom_q%sym_walls(1) = wall_t(point=[0.0_rk, 0.0_rk, 0.0_rk], normal=[1.0_rk, 0.0_rk, 0.0_rk])
  dom_q%sym_walls(2) = wall_t(point=[0.0_rk, 0.0_rk, 0.0_rk], normal=[0.0_rk, 1.0_rk, 0.0_rk])
  ! the quarter, and the full model: the quarter and its three mirror images
  sq = 0
  call quarter_and_full(quarter, full)
  call fill(lone, nq)
  lone%x(:,1:nq) = xq
  lone%v(:,1:nq) = vq
  dt = 1e-9_rk
  call particles_forces(quarter, dom_q%sym_walls, dom_q%mat, dt)
  call particles_forces(full, dom_f%sym_walls, dom_f%mat, dt)
  call particles_forces(lone, dom_n%sym_walls, dom_n%mat, dt)
  call check('images_made', quarter%n_ghosts > nq/4, itoa(quarter%n_ghosts)//' images of '//itoa(nq)//' particles')
  err_a = maxval(abs(quarter%acc(:,1:nq) - full%acc(:,1:nq)))
  scale_a = maxval(abs(full%acc(:,1:nq)))
  call check('quarter_accelerations_are_the_full_models', err_a < 1e-12_rk*scale_a, &
             'largest difference '//r2s(err_a/scale_a)//' of the largest acceleration')
  err_a = maxval(abs(lone%acc(:,1:nq) - full%acc(:,1:nq)))
  call check('without_images_they_differ', err_a > 1e-3_rk*scale_a, &
             'no planes: largest difference '//r2s(err_a/scale_a)//' of the largest acceleration')
  call particles_move(quarter, dt)
  call particles_move(full, dt)
  call particles_finish_step(quarter, dom_q, dt)
  call particles_finish_step(full, dom_f, dt)
  err_r = maxval(abs(quarter%drho(1:nq) - full%drho(1:nq)))
  scale_r = maxval(abs(full%drho(1:nq)))
  err_h = maxval(abs(quarter%dheat(1:nq) - full%dheat(1:nq)))
  scale_h = maxval(abs(full%dheat(1:nq)))
  call check('quarter_density_rates_are_the_full_models', err_r < 1e-12_rk*scale_r, &
             'largest difference '//r2s(err_r/scale_r)//' of the largest rate')
  call check('quarter_heating_is_the_full_models', err_h < 1e-12_rk*scale_h .and. scale_h > 0.0_rk, &
             'largest difference '//r2s(err_h/scale_h)//' of the largest heating')
  err_a = 0
  do k = 1, nq
    err_a = max(err_a, norm2(quarter%x(:,k) - full%x(:,k)))
  end do
  call check('quarter_positions_are_the_full_models', err_a < 1e-15_rk, 'largest difference '//r2s(err_a)//' m')
  ! strong particles in tension (p -2 GPa) with a random deviator: the
  ! images carry the mirrored stress and its artificial stress
  do i = 1, nq
    call random_number(sq(:,i))
    sq(:,i) = 1e9_rk*(sq(:,i) - 0.5_rk)
    sq(1:3,i) = sq(1:3,i) - sum(sq(1:3,i))/3
  end do
  call quarter_and_full(tq, tf)
  tq%p(1:nq) = -2e9_rk
  tf%p(1:4*nq) = -2e9_rk
  tq%strong(1:nq) = .true.
  tf%strong(1:4*nq) = .true.
  dom_q%mat(1)%artificial_stress = 0.3_rk
  dom_f%mat(1)%artificial_stress = 0.3_rk
  call particles_forces(tq, dom_q%sym_walls, dom_q%mat, dt)
  call particles_forces(tf, dom_f%sym_walls, dom_f%mat, dt)
  err_a = maxval(abs(tq%acc(:,1:nq) - tf%acc(:,1:nq)))
  scale_a = maxval(abs(tf%acc(:,1:nq)))
  call check('strong_quarter_accelerations_are_the_full_models', err_a < 1e-12_rk*scale_a .and. tq%artificial, &
             'largest difference '//r2s(err_a/scale_a)//' of the largest acceleration')
  call particles_move(tq, dt)
  call particles_move(tf, dt)
  tq%dheat = 0
  tf%dheat = 0
  call particles_finish_step(tq, dom_q, dt)
  call particles_finish_step(tf, dom_f, dt)
  err_h = maxval(abs(tq%e(1:nq) - tf%e(1:nq)))
  scale_h = maxval(abs(tf%e(1:nq)))
  call check('strong_quarter_energies_are_the_full_models', err_h < 1e-12_rk*scale_h .and. scale_h > 0.0_rk, &
             'largest difference '//r2s(err_h/scale_h)//' of the largest specific energy')
  ! a sparse cloud (particles metres apart, h 0.7 mm): the pair search's
  ! grid takes its most cells, 2 per particle, more than the particles'
  ! room; 0.6.1 wrote the cells' fill pointers past the end of a work
  ! array sized by the particles (the heap corruption that stopped the
  ! normal cylinder with particles; this debug build's bounds check
  ! stopped here)
  call fill(sparse, 64)
  do i = 1, 64
    call random_number(u)
    sparse%x(:,i) = u
    sparse%v(:,i) = 0
  end do
  call particles_forces(sparse, dom_n%sym_walls, dom_n%mat, dt)
  call check('sparse_cloud_has_no_pairs', sparse%n_pairs == 0, itoa(sparse%n_pairs)//' pairs among 64 particles')
  call check_summary()

contains

  !> The quarter (xq, vq, sq) as its own particles, and the full model:
  !> the quarter and its three mirror images (positions, velocities and
  !> the deviator mirrored).
  subroutine quarter_and_full(qt, fl)
    type(particles_t), intent(inout) :: qt, fl
    real(rk) :: flip(6)
    integer :: i, s, q
    call fill(qt, nq)
    call fill(fl, 4*nq)
    ! (Balsara's switch on: the images take their originals' factors)
    qt%use_shear_switch = .true.
    fl%use_shear_switch = .true.
    do i = 1, nq
      do s = 0, 3
        q = s*nq + i
        fl%x(:,q) = xq(:,i)*[merge(-1, 1, btest(s, 0)), merge(-1, 1, btest(s, 1)), 1]
        fl%v(:,q) = vq(:,i)*[merge(-1, 1, btest(s, 0)), merge(-1, 1, btest(s, 1)), 1]
        ! (xx,yy,zz,xy,yz,zx): x -> -x flips xy and zx, y -> -y flips xy and yz
        flip = 1
        if (btest(s, 0)) flip = flip*[1, 1, 1, -1, 1, -1]
        if (btest(s, 1)) flip = flip*[1, 1, 1, -1, -1, 1]
        fl%s(:,q) = flip*sq(:,i)
      end do
      qt%x(:,i) = xq(:,i)
      qt%v(:,i) = vq(:,i)
      qt%s(:,i) = sq(:,i)
    end do
  end subroutine

  subroutine material(dom)
    type(domain_t), intent(inout) :: dom
    allocate(dom%mat(1))
    dom%mat(1)%rho0 = 7850.0_rk
    dom%mat(1)%eos = eos_linear
    dom%mat(1)%bulk_modulus = 160e9_rk
    dom%mat(1)%eroded = eroded_particles
  end subroutine

  !> n steel particles of 1 mg, compressed by 2 % (they push).
  subroutine fill(pt, n)
    type(particles_t), intent(inout) :: pt
    integer, intent(in) :: n
    call particles_reserve(pt, n)
    pt%n = n
    pt%m(1:n) = 1e-6_rk
    pt%rho(1:n) = 1.02_rk*7850.0_rk
    pt%e(1:n) = 0
    pt%p(1:n) = 160e9_rk*0.02_rk
    pt%c(1:n) = sqrt(160e9_rk/7850.0_rk)
    pt%h(1:n) = 0.7e-3_rk
    pt%mat(1:n) = 1
    pt%part(1:n) = 1
  end subroutine
end program test_particle_ghosts
