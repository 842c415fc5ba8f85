!> Unit tests of the 2D contact geometry (udar_segment2, issue 14 item 3):
!> the segment projection by hand, the shares (distance = linear
!> interpolation on the segment; area: no moment about the start
!> positions), the 3D velocity matching with a segment's two master nodes
!> (a third of weight 0 takes no part; normal velocities matched, momentum
!> exact) and the area coordinates in a triangle.
program test_segment2
  use udar_kinds, only: rk
  use udar_strings, only: r2s
  use udar_config, only: contact_weights_distance, contact_weights_area
  use udar_segment2, only: segment_projection, segment_shares, triangle_coordinates, closest_on_segment
  use udar_contact_kernels, only: match_velocities, contact_point, triangle_projection
  use udar_contact_faces, only: face_projection, face_shares, closest_on_face, element_coordinates
  use unit_checks, only: check, check_summary
  implicit none
  real(rk) :: xa(3,2), xs(3), n(3), dist, g(2), r(2), xa0(3,2), xs0(3), p(3), lam(3), tri(3,3)
  real(rk) :: ms, vs(3), mm(3), vm(3,3), g3(3), r3(3), dvs(3), dvm(3,3), dn, dtv(3), vs_after(3), vm_after(3,3), &
              mom(3), rel(3)
  logical :: acted
  real(rk) :: n1(3), d1, g31(3), g32(3), c(3), lam4(4), r3b(3)

  ! a master segment along +x: the master element lies above it (the
  ! boundary counter-clockwise), so its outward normal points down
  xa(:,1) = [0.0_rk, 0.0_rk, 0.0_rk]
  xa(:,2) = [2.0_rk, 0.0_rk, 0.0_rk]
  xs = [0.5_rk, -0.3_rk, 0.0_rk]
  call segment_projection(xa, xs, n, dist, g)
  call check('projection_by_hand', all(abs(n - [0.0_rk, -1.0_rk, 0.0_rk]) < 1e-15_rk) .and. &
             abs(dist - 0.3_rk) < 1e-15_rk .and. all(abs(g - [0.75_rk, 0.25_rk]) < 1e-15_rk), &
             'n = ('//r2s(n(1))//', '//r2s(n(2))//'), dist '//r2s(dist)//', g '//r2s(g(1))//' '//r2s(g(2)))
  xs = [1.5_rk, 0.2_rk, 0.0_rk]
  call segment_projection(xa, xs, n, dist, g)
  call check('node_behind_the_segment', abs(dist + 0.2_rk) < 1e-15_rk .and. abs(g(2) - 0.75_rk) < 1e-15_rk, &
             'dist '//r2s(dist)//' (negative: behind), g '//r2s(g(1))//' '//r2s(g(2)))

  ! distance shares of a point on the segment: the linear interpolation
  xs = [0.5_rk, 0.0_rk, 0.0_rk]
  call segment_projection(xa, xs, n, dist, g)
  call segment_shares(contact_weights_distance, xa, xs, g, n, xa, xs, r)
  call check('distance_shares_on_the_segment_are_linear', all(abs(r - [0.75_rk, 0.25_rk]) < 1e-15_rk), &
             'R = '//r2s(r(1))//' '//r2s(r(2)))
  xs = xa(:,2)
  call segment_shares(contact_weights_distance, xa, xs, [0.0_rk, 1.0_rk], n, xa, xs, r)
  call check('distance_shares_at_a_node', all(r == [0.0_rk, 1.0_rk]), 'R = '//r2s(r(1))//' '//r2s(r(2)))
  ! area shares without motion: the projection's coordinates
  xs = [1.2_rk, 0.1_rk, 0.0_rk]
  call segment_projection(xa, xs, n, dist, g)
  call segment_shares(contact_weights_area, xa, xs, g, n, xa, xs, r)
  call check('area_shares_without_motion_are_g', all(abs(r - g) < 1e-15_rk), 'R = '//r2s(r(1))//' '//r2s(r(2)))
  ! with motion: the line through the slave node's start along n meets the
  ! start segment at sum_a R_a xa0 (no moment about the start positions)
  xa0(:,1) = [0.1_rk, -0.2_rk, 0.0_rk]
  xa0(:,2) = [2.05_rk, 0.15_rk, 0.0_rk]
  xs0 = [0.8_rk, -0.6_rk, 0.0_rk]
  call segment_shares(contact_weights_area, xa, xs, g, n, xa0, xs0, r)
  p = r(1)*xa0(:,1) + r(2)*xa0(:,2) - xs0
  call check('area_shares_no_moment_about_the_start', abs(p(1)*n(2) - p(2)*n(1)) < 1e-14_rk .and. &
             abs(r(1) + r(2) - 1.0_rk) < 1e-15_rk, 'moment arm '//r2s(p(1)*n(2) - p(2)*n(1))//', R = '// &
             r2s(r(1))//' '//r2s(r(2)))

  ! the 3D matching with the segment's two nodes and a third of weight 0
  xs = [0.5_rk, -0.01_rk, 0.0_rk]            ! just in front: contact point g = (0.75, 0.25)
  call segment_projection(xa, xs, n, dist, g)
  ms = 2.0_rk
  vs = [0.3_rk, 1.0_rk, 0.0_rk]              ! closing on the segment (moving up, n points down)
  mm = [3.0_rk, 5.0_rk, 7.0_rk]
  vm(:,1) = [0.0_rk, -0.2_rk, 0.0_rk]
  vm(:,2) = [0.1_rk, 0.1_rk, 0.0_rk]
  vm(:,3) = [9.0_rk, 9.0_rk, 0.0_rk]         ! the unused slot: must not matter
  g3 = [g(1), g(2), 0.0_rk]
  r3 = [g(1), g(2), 0.0_rk]
  call match_velocities(n, ms, vs, mm, vm, g3, r3, 0.3_rk, 0.0_rk, [0.0_rk, 0.0_rk, 0.0_rk], dvs, dvm, acted, dn, dtv)
  vs_after = vs + dvs
  vm_after = vm + dvm
  rel = contact_point(g3)
  p = rel(1)*vm_after(:,1) + rel(2)*vm_after(:,2) + rel(3)*vm_after(:,3)
  mom = ms*dvs + mm(1)*dvm(:,1) + mm(2)*dvm(:,2) + mm(3)*dvm(:,3)
  call check('segment_matching_normal_velocities_equal', acted .and. abs(dot_product(n, p - vs_after)) < 1e-15_rk, &
             'normal velocities after: slave '//r2s(dot_product(n, vs_after))//', segment '//r2s(dot_product(n, p)))
  call check('segment_matching_momentum_exact_third_slot_untouched', maxval(abs(mom)) < 1e-15_rk .and. &
             all(dvm(:,3) == 0.0_rk) .and. rel(3) == 0.0_rk, 'momentum change '//r2s(maxval(abs(mom))))

  ! area coordinates in a triangle
  tri(:,1) = [0.0_rk, 0.0_rk, 0.0_rk]
  tri(:,2) = [1.0_rk, 0.0_rk, 0.0_rk]
  tri(:,3) = [0.0_rk, 1.0_rk, 0.0_rk]
  call triangle_coordinates(tri, [1.0_rk/3, 1.0_rk/3, 0.0_rk], lam)
  call check('triangle_coordinates_centroid', all(abs(lam - 1.0_rk/3) < 1e-15_rk), &
             r2s(lam(1))//' '//r2s(lam(2))//' '//r2s(lam(3)))
  call triangle_coordinates(tri, [0.8_rk, 0.4_rk, 0.0_rk], lam)
  call check('triangle_coordinates_outside', abs(lam(1) + 0.2_rk) < 1e-15_rk .and. minval(lam) < 0.0_rk, &
             r2s(lam(1))//' '//r2s(lam(2))//' '//r2s(lam(3)))

  ! the face dispatch (udar_contact_faces): a triangle's the 3D kernel's
  ! to the bit, a segment's the 2D kernel's with a third entry 0
  tri(:,1) = [0.1_rk, 0.2_rk, 0.3_rk]
  tri(:,2) = [1.2_rk, 0.1_rk, -0.2_rk]
  tri(:,3) = [0.4_rk, 1.3_rk, 0.5_rk]
  xs = [0.5_rk, 0.4_rk, 0.9_rk]
  call triangle_projection(tri, xs, n, dist, g31)
  call face_projection(tri, xs, n1, d1, g32)
  call check('face_projection_of_a_triangle_is_the_3d_kernel', all(n1 == n) .and. d1 == dist .and. all(g32 == g31), &
             'dist '//r2s(d1))
  xs = [0.5_rk, -0.3_rk, 0.0_rk]
  call face_projection(xa, xs, n1, d1, g31)
  call segment_projection(xa, xs, n, dist, g)
  call check('face_projection_of_a_segment_is_the_2d_kernel', all(n1 == n) .and. d1 == dist .and. &
             all(g31 == [g(1), g(2), 0.0_rk]), 'g '//r2s(g31(1))//' '//r2s(g31(2))//' '//r2s(g31(3)))
  call face_shares(contact_weights_area, xa, xs, g31, n1, xa, xs, r3b)
  call check('face_shares_of_a_segment', all(abs(r3b - [0.75_rk, 0.25_rk, 0.0_rk]) < 1e-15_rk), &
             'R '//r2s(r3b(1))//' '//r2s(r3b(2))//' '//r2s(r3b(3)))
  call closest_on_face(xa, [2.5_rk, 0.4_rk, 0.0_rk], c, g31)
  call check('closest_on_a_segment_beyond_its_end', all(c == xa(:,2)) .and. all(g31 == [0.0_rk, 1.0_rk, 0.0_rk]), &
             'c = ('//r2s(c(1))//', '//r2s(c(2))//')')
  call element_coordinates(xa, [1.0_rk, 1.0_rk, 0.0_rk], [1.0_rk, 0.25_rk, 0.0_rk], lam4)
  call check('element_coordinates_in_a_2d_triangle', all(abs(lam4 - [0.375_rk, 0.375_rk, 0.25_rk, 0.0_rk]) < 1e-15_rk), &
             r2s(lam4(1))//' '//r2s(lam4(2))//' '//r2s(lam4(3))//' '//r2s(lam4(4)))
  call check_summary()
end program test_segment2
