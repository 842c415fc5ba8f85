!> Unit tests of the closed voids' kernel (udar_eroded_voids, &contact
!> voids): the volume gradients by hand and against finite differences; a
!> void turned inside out and still closing loses exactly its closing rate
!> (dV/dt = 0 after), with momentum and angular momentum unchanged and the
!> kinetic energy lost as the formula says; a void opening again, one not
!> inverted, or one with a massless corner is left alone; a corner on a
!> symmetry plane (its projector) moves only in the plane and the rate is
!> still stopped; splitting the masses (what voids_enforce does where
!> voids share nodes) never adds kinetic energy, where summing the voids'
!> own changes does (the energy the penetration deck gained before it:
!> validation.md 4zi).
program test_eroded_voids
  use udar_kinds, only: rk
  use udar_strings, only: r2s
  use udar_vectors, only: cross
  use udar_eroded_voids, only: void_changes, volume_gradients
  use unit_checks, only: check, check_summary
  implicit none
  real(rk) :: x(3,4), v(3,4), m(4), p(3,3,4), dv(3,4), g(3,4), vol, gd(3,4), gw(3,4), xp(3,4), vp, vm, eps
  real(rk) :: rate, rate_after, mom(3), ang(3), ke0, ke1, w, lam
  real(rk) :: xb(3,5), vb(3,5), mb(5), dvb(3,4,3), vsum(3,5), vsplit(3,5), share(5), ke_sum, ke_split, ke_b
  integer :: a, c, k, conn(4,3)
  logical :: held

  p = 0
  do a = 1, 4
    do c = 1, 3
      p(c,c,a) = 1
    end do
  end do
  ! the unit corner tetrahedron, volume 1/6, gradients by hand
  x = reshape([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1], [3, 4])*1.0_rk
  call volume_gradients(x, g, vol)
  call check('volume_by_hand', abs(vol - 1.0_rk/6.0_rk) < 1e-16_rk, 'V = '//r2s(vol))
  call check('gradients_by_hand', all(abs(g(:,2) - [1, 0, 0]/6.0_rk) < 1e-16_rk) .and. &
             all(abs(g(:,3) - [0, 1, 0]/6.0_rk) < 1e-16_rk) .and. all(abs(g(:,4) - [0, 0, 1]/6.0_rk) < 1e-16_rk) &
             .and. all(abs(g(:,1) + 1.0_rk/6.0_rk) < 1e-16_rk), 'g_1 = '//r2s(g(1,1)))
  ! inside out: the apex through the opposite face, skewed, still closing
  x(:,4) = [0.3_rk, 0.2_rk, -0.1_rk]
  x(:,2) = [1.1_rk, 0.1_rk, 0.05_rk]
  call volume_gradients(x, g, vol)
  eps = 1e-7_rk
  do a = 1, 4
    do c = 1, 3
      xp = x; xp(c,a) = xp(c,a) + eps
      call volume_gradients(xp, gw, vp)
      xp = x; xp(c,a) = xp(c,a) - eps
      call volume_gradients(xp, gw, vm)
      gd(c,a) = (vp - vm)/(2*eps)
    end do
  end do
  call volume_gradients(x, g, vol)
  call check('gradients_against_finite_differences', maxval(abs(g - gd)) < 1e-9_rk, &
             'largest difference '//r2s(maxval(abs(g - gd))))
  call check('the_test_void_is_inverted', vol < 0.0_rk, 'V = '//r2s(vol))
  v = reshape([0.2_rk, -0.1_rk, 0.3_rk, -0.4_rk, 0.1_rk, 0.0_rk, 0.1_rk, 0.5_rk, -0.2_rk, 0.3_rk, -0.2_rk, -2.0_rk], &
              [3, 4])
  m = [1.0_rk, 2.0_rk, 0.5_rk, 3.0_rk]
  rate = sum(g*v)
  call check('the_test_void_is_closing', rate < 0.0_rk, 'dV/dt = '//r2s(rate))
  call void_changes(x, v, m, p, dv, held)
  rate_after = sum(g*(v + dv))
  mom = 0
  ang = 0
  do a = 1, 4
    mom = mom + m(a)*dv(:,a)
    ang = ang + m(a)*cross(x(:,a), dv(:,a))
  end do
  call check('held_and_its_closing_rate_stopped', held .and. abs(rate_after) < 1e-15_rk*abs(rate), &
             'dV/dt '//r2s(rate)//' -> '//r2s(rate_after))
  call check('momentum_unchanged', maxval(abs(mom)) < 1e-15_rk, 'sum m dv = '//r2s(maxval(abs(mom))))
  call check('angular_momentum_unchanged', maxval(abs(ang)) < 1e-15_rk, 'sum m x x dv = '//r2s(maxval(abs(ang))))
  ke0 = 0.5_rk*sum(spread(m, 1, 3)*v**2)
  ke1 = 0.5_rk*sum(spread(m, 1, 3)*(v + dv)**2)
  w = sum(sum(g**2, dim=1)/m)
  lam = rate/w
  call check('kinetic_energy_lost_as_the_formula', abs((ke0 - ke1) - 0.5_rk*lam**2*w) < 1e-14_rk*ke0, &
             'lost '//r2s(ke0 - ke1)//', lambda^2 w / 2 = '//r2s(0.5_rk*lam**2*w))
  ! opening again, not inverted, a massless corner: no change
  call void_changes(x, -v, m, p, dv, held)
  call check('an_opening_void_is_left_alone', .not. held .and. all(dv == 0.0_rk), '')
  xp = x
  xp(:,4) = [0.3_rk, 0.2_rk, 0.4_rk]
  call void_changes(xp, v, m, p, dv, held)
  call check('a_void_not_inverted_is_left_alone', .not. held .and. all(dv == 0.0_rk), '')
  call void_changes(x, v, [1.0_rk, 0.0_rk, 1.0_rk, 1.0_rk], p, dv, held)
  call check('a_massless_corner_leaves_it_alone', .not. held .and. all(dv == 0.0_rk), '')
  ! corner 4 on the symmetry plane y = 0: no velocity across it
  p(2,2,4) = 0
  call void_changes(x, v, m, p, dv, held)
  call check('a_corner_on_a_symmetry_plane_moves_in_it', held .and. dv(2,4) == 0.0_rk .and. &
             abs(sum(g*(v + dv))) < 1e-15_rk*abs(rate), 'dv_y '//r2s(dv(2,4))//', dV/dt after '//r2s(sum(g*(v + dv))))
  p(2,2,4) = 1

  ! three inverted voids sharing a node (node 5 the apex of all three,
  ! driven through their common base region): their own changes summed
  ! overshoot and add kinetic energy; the changes on the mass shares
  ! (m_a / n_a, n_a the voids at node a), averaged, lose energy
  xb(:,1) = [0.0_rk, 0.0_rk, 0.0_rk]
  xb(:,2) = [1.0_rk, 0.0_rk, 0.0_rk]
  xb(:,3) = [0.0_rk, 1.0_rk, 0.0_rk]
  xb(:,4) = [1.0_rk, 1.0_rk, 0.0_rk]
  xb(:,5) = [0.45_rk, 0.45_rk, -0.05_rk]
  conn(:,1) = [1, 2, 3, 5]
  conn(:,2) = [2, 4, 3, 5]
  conn(:,3) = [1, 2, 4, 5]
  vb = 0
  vb(:,5) = [0.0_rk, 0.0_rk, -1.0_rk]
  mb = [1.0_rk, 1.0_rk, 1.0_rk, 1.0_rk, 0.2_rk]
  share = 0
  do k = 1, 3
    call volume_gradients(xb(:,conn(:,k)), g, vol)
    if (vol < 0.0_rk) share(conn(:,k)) = share(conn(:,k)) + 1
  end do
  call check('three_inverted_voids_at_node_5', share(5) == 3.0_rk, 'voids at node 5: '//r2s(share(5)))
  vsum = vb
  vsplit = vb
  do k = 1, 3
    call void_changes(xb(:,conn(:,k)), vb(:,conn(:,k)), mb(conn(:,k)), p, dvb(:,:,k), held)
    vsum(:,conn(:,k)) = vsum(:,conn(:,k)) + dvb(:,:,k)
    call void_changes(xb(:,conn(:,k)), vb(:,conn(:,k)), mb(conn(:,k))/share(conn(:,k)), p, dvb(:,:,k), held)
    vsplit(:,conn(:,k)) = vsplit(:,conn(:,k)) + dvb(:,:,k)/spread(share(conn(:,k)), 1, 3)
  end do
  ke_b = 0.5_rk*sum(spread(mb, 1, 3)*vb**2)
  ke_sum = 0.5_rk*sum(spread(mb, 1, 3)*vsum**2)
  ke_split = 0.5_rk*sum(spread(mb, 1, 3)*vsplit**2)
  call check('summing_the_voids_own_changes_adds_energy', ke_sum > ke_b, &
             'KE '//r2s(ke_b)//' -> '//r2s(ke_sum))
  call check('the_mass_shares_lose_energy', ke_split < ke_b, 'KE '//r2s(ke_b)//' -> '//r2s(ke_split))
  mom = sum(spread(mb, 1, 3)*(vsplit - vb), dim=2)
  call check('the_mass_shares_keep_momentum', maxval(abs(mom)) < 1e-15_rk, 'sum m dv = '//r2s(maxval(abs(mom))))
  call check_summary()
end program test_eroded_voids
