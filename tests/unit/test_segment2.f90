!> Unit tests of the 2D contact geometry (udar_segment2, issue 14 item 3):
!> the segment projection by hand, the shares (distance = linear
!> interpolation on the segment; area: no moment about the start
!> positions), the 3D velocity matching with a segment's two master nodes
!> (a third of weight 0 takes no part; normal velocities matched, momentum
!> exact) and the area coordinates in a triangle; where a node behind a
!> segment's line beyond its end is (face_behind_surface: a rim, a
!> convex or straight corner, the seam of a concave one) and whether it is
!> outside beside a sharp corner (face_beside_sharp_edge), by hand, for a
!> triangle and a segment in the contact driver's 3D-layout arrays.
program test_segment2
  use udar_kinds, only: rk
  use udar_strings, only: r2s
  use udar_config, only: contact_weights_distance, contact_weights_area
  use udar_segment2, only: segment_projection, segment_shares, triangle_coordinates, closest_on_segment
  use udar_contact_kernels, only: match_velocities, contact_point, triangle_projection, behind_not, behind_face, &
                                  behind_seam
  use udar_contact_faces, only: face_projection, face_shares, closest_on_face, element_coordinates, &
                                face_behind_surface, face_beside_sharp_edge
  use unit_checks, only: check, check_summary, logicals
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
  call test_segment_seams()
  call test_segment_corners()
  call test_face_dispatch()
  call check_summary()
contains

  !> Where a node behind a segment's line is when its projection falls
  !> beyond an end (face_behind_surface), by hand. The master segment
  !> S = (2,0) -> (0,0) is the top of a body below y = 0 (outward n =
  !> (0,1)); a node (x, y) has dist = y and g = (x/2, 1 - x/2): g(1) < 0
  !> (x < 0) is beyond node 2 = (0,0), across which xb(:,:,1) lies; g(2) < 0
  !> (x > 2) beyond node 1 = (2,0), xb(:,:,2). tol 1e-3.
  subroutine test_segment_seams()
    real(rk) :: xa(3,2), xb(3,2,2), xv(3,2), xvb(3,2,2), n(3), dist, g(2)
    logical :: has(2)
    integer :: v(2)
    xa(:,1) = [2.0_rk, 0.0_rk, 0.0_rk]
    xa(:,2) = [0.0_rk, 0.0_rk, 0.0_rk]
    xb = 0
    has = .false.
    ! (0.5,-0.1): dist -0.1, g = (0.25, 0.75), on S: behind_face
    call segment_projection(xa, [0.5_rk, -0.1_rk, 0.0_rk], n, dist, g)
    v(1) = verdict2(xa, xb, has, [0.5_rk, -0.1_rk, 0.0_rk])
    call check('segment_seam_on_the_segment', v(1) == behind_face .and. abs(dist + 0.1_rk) < 1e-15_rk .and. &
               all(abs(g - [0.25_rk, 0.75_rk]) < 1e-15_rk), 'verdict '//trim(ints(v(1:1)))//' (1 wanted), dist '// &
               r2s(dist)//', g '//r2s(g(1))//' '//r2s(g(2)))
    ! (2.1,-0.1): g = (1.05, -0.05), beyond node 1 with nothing there (a rim): behind_not
    v(1) = verdict2(xa, xb, has, [2.1_rk, -0.1_rk, 0.0_rk])
    call check('segment_seam_rim', v(1) == behind_not, 'verdict '//trim(ints(v(1:1)))//' (0 wanted)')
    ! the same node at the square's corner: the side (2,-2) -> (2,0) falls
    ! away under S (its centre (2,-1) is 1 behind S's line): convex, the
    ! side has the node if anyone: behind_not; a straight continuation
    ! (4,0) -> (2,0) (centre on the line): behind_not too
    has(2) = .true.
    xb(:,1,2) = [2.0_rk, -2.0_rk, 0.0_rk]
    xb(:,2,2) = [2.0_rk, 0.0_rk, 0.0_rk]
    v(1) = verdict2(xa, xb, has, [2.1_rk, -0.1_rk, 0.0_rk])
    xb(:,1,2) = [4.0_rk, 0.0_rk, 0.0_rk]
    v(2) = verdict2(xa, xb, has, [2.1_rk, -0.1_rk, 0.0_rk])
    call check('segment_seam_convex_and_straight_corners', all(v == [behind_not, behind_not]), &
               'square corner, straight: '//trim(ints(v))//' (0 0 wanted)')
    ! a concave corner at 90 degrees (a step: the wall (0,0) -> (0,2) rises
    ! from S's end, outward (1,0); the empty quadrant x, y > 0): a node at
    ! x < 0, y < 0 is behind both lines, -x beyond S's end at depth -y; the
    ! normals are 90 degrees apart: the gap is tan(45) = 1 times the depth.
    ! (-0.1,-0.3): 0.1 beyond, within 0.3: behind_seam; (-0.4,-0.3): 0.4
    ! beyond the gap 0.3: behind_not
    has = [.true., .false.]
    xb(:,1,1) = [0.0_rk, 0.0_rk, 0.0_rk]
    xb(:,2,1) = [0.0_rk, 2.0_rk, 0.0_rk]
    v(1) = verdict2(xa, xb, has, [-0.1_rk, -0.3_rk, 0.0_rk])
    v(2) = verdict2(xa, xb, has, [-0.4_rk, -0.3_rk, 0.0_rk])
    call check('segment_seam_concave_step_90', all(v == [behind_seam, behind_not]), &
               'in the gap, beyond it: '//trim(ints(v))//' (2 0 wanted)')
    ! the wall rising at 45 degrees ((0,0) -> (-1,1), outward (1,1)/sqrt 2):
    ! the normals 45 degrees apart, the gap tan(22.5) = 0.4142 of the depth:
    ! at depth 0.3 0.1243. (-0.1,-0.3): 0.1 beyond: behind_seam;
    ! (-0.15,-0.3): 0.15 beyond: behind_not (it would be in a 90-degree gap)
    xb(:,2,1) = [-1.0_rk, 1.0_rk, 0.0_rk]
    v(1) = verdict2(xa, xb, has, [-0.1_rk, -0.3_rk, 0.0_rk])
    v(2) = verdict2(xa, xb, has, [-0.15_rk, -0.3_rk, 0.0_rk])
    call check('segment_seam_concave_fold_45', all(v == [behind_seam, behind_not]), &
               'in the gap, beyond it: '//trim(ints(v))//' (2 0 wanted)')
    ! a V-shaped dent, its arms meeting at 90 degrees at the origin (the
    ! body below y = |x|): S' = (1,1) -> (0,0) (outward (-1,1)/sqrt 2),
    ! across its node 2 the arm (0,0) -> (-1,1) (outward (1,1)/sqrt 2). A
    ! node (x, y) is (x - y)/sqrt 2 deep behind S' and -(x + y)/sqrt 2
    ! beyond its end (g(1) = (x + y)/2); the gap tan(45) times the depth.
    ! (0.05,-0.2): depth 0.1768, 0.1061 beyond: behind_seam; (-0.05,-0.3):
    ! the same depth, 0.2475 beyond: behind_not
    xv(:,1) = [1.0_rk, 1.0_rk, 0.0_rk]
    xv(:,2) = [0.0_rk, 0.0_rk, 0.0_rk]
    xvb = 0
    xvb(:,1,1) = [0.0_rk, 0.0_rk, 0.0_rk]
    xvb(:,2,1) = [-1.0_rk, 1.0_rk, 0.0_rk]
    v(1) = verdict2(xv, xvb, has, [0.05_rk, -0.2_rk, 0.0_rk])
    v(2) = verdict2(xv, xvb, has, [-0.05_rk, -0.3_rk, 0.0_rk])
    call check('segment_seam_v_dent_90', all(v == [behind_seam, behind_not]), &
               'in the gap, beyond it: '//trim(ints(v))//' (2 0 wanted)')
  end subroutine

  !> Whether a node behind a segment's line is outside the body beside a
  !> sharp corner (face_beside_sharp_edge), by hand. S = (2,0) -> (0,0), the
  !> top (outward (0,1), g(1) = x/2); across its node 2 (shares = (F, T)) a
  !> side falling away under it. A wedge of 60 degrees: the side (0,0) ->
  !> (1,-sqrt 3), outward -(sqrt 3, 1)/2, a node's distance from it
  !> dk = -(sqrt 3 x + y)/2 and its coordinate along it (x - sqrt 3 y)/4.
  subroutine test_segment_corners()
    real(rk) :: xa(3,2), xb(3,2,1)
    logical :: shares(2,1), v(6)
    xa(:,1) = [2.0_rk, 0.0_rk, 0.0_rk]
    xa(:,2) = [0.0_rk, 0.0_rk, 0.0_rk]
    shares(:,1) = [.false., .true.]
    xb(:,1,1) = [0.0_rk, 0.0_rk, 0.0_rk]
    xb(:,2,1) = [1.0_rk, -sqrt(3.0_rk), 0.0_rk]
    ! (0.2,-0.4): 0.4 behind S, g(1) = 0.1; dk = 0.0268 (just outside the
    ! side), 0.223 along it: outside
    v(1) = outside2(xa, xb, shares, 1, [0.2_rk, -0.4_rk, 0.0_rk])
    ! (0.5,-0.2): dk = -0.333, inside the wedge (behind both lines): not
    v(2) = outside2(xa, xb, shares, 1, [0.5_rk, -0.2_rk, 0.0_rk])
    ! (1.5,-3): dk = 0.201 in front of the side's line but 1.674 along it
    ! (beyond its far end): not
    v(3) = outside2(xa, xb, shares, 1, [1.5_rk, -3.0_rk, 0.0_rk])
    ! on the side's line, a quarter along it (dk 0 within rounding): outside
    v(4) = outside2(xa, xb, shares, 1, 0.25_rk*xb(:,2,1))
    ! (0.001,-0.1): outside the side (dk 0.0491, 0.0436 along it) but
    ! g(1) = 0.0005 <= tol, its projection on S at the shared node: not
    v(5) = outside2(xa, xb, shares, 1, [0.001_rk, -0.1_rk, 0.0_rk])
    ! (0.2,-0.4) with no side given (nb = 0): not
    v(6) = outside2(xa, xb, shares, 0, [0.2_rk, -0.4_rk, 0.0_rk])
    call check('segment_corner_wedge_60', all(v .eqv. [.true., .false., .false., .true., .false., .false.]), &
               'outside / inside / beyond the far end / on the line / at the shared node / none, TFFTFF wanted: '// &
               trim(logicals(v)))
    ! a square corner: the side (0,0) -> (0,-2), outward (-1,0). (0,-0.3) on
    ! the side's line and (-0.01,-0.3) just outside it project onto S at or
    ! beyond the corner (g(1) = 0, -0.005): not; (0.05,-0.02), under the
    ! top face near the corner (it crossed it; g(1) = 0.025), is behind the
    ! side (dk = -0.05): not
    xb(:,2,1) = [0.0_rk, -2.0_rk, 0.0_rk]
    v(1) = outside2(xa, xb, shares, 1, [0.0_rk, -0.3_rk, 0.0_rk])
    v(2) = outside2(xa, xb, shares, 1, [-0.01_rk, -0.3_rk, 0.0_rk])
    v(3) = outside2(xa, xb, shares, 1, [0.05_rk, -0.02_rk, 0.0_rk])
    ! a rising (concave) side (0,0) -> (-1,1) (centre in front of S): not,
    ! for the node that was outside the wedge
    xb(:,2,1) = [-1.0_rk, 1.0_rk, 0.0_rk]
    v(4) = outside2(xa, xb, shares, 1, [0.2_rk, -0.4_rk, 0.0_rk])
    call check('segment_corner_square_and_rising', all(.not. v(1:4)), &
               'on the side / outside it / crossed the top / rising, FFFF wanted: '//trim(logicals(v(1:4))))
  end subroutine

  !> face_behind_surface and face_beside_sharp_edge on a triangle and on a
  !> segment, in arrays laid out as the contact driver's (3 corners, 3
  !> faces beside; a segment's third entries ignored: filled with junk
  !> here). Each on two nodes with different answers.
  subroutine test_face_dispatch()
    real(rk) :: tri(3,3), xb(3,3,3), xs1(3,3,1), n(3), dist, g(3), p(3,2), seg(3,2)
    logical :: has(3), shares(3,1), bf(2)
    integer :: vf(2), k
    ! test_contact_kernels' triangle T = (0,0,0), (1,0.5,0), (0,1,0) (z = 0,
    ! outward +z). Across its edge x = 0 a concave face rising at 45
    ! degrees: (-0.005,0.3,-0.02) in the seam (2), (-0.01,0.3,-0.02) beyond
    ! it (0). A face falling under T to (0.5,0.5,-1) (63.4 degrees):
    ! (0.3,0.5,-0.8) outside beside it (T), (0.3,0.5,-0.3) inside (F).
    tri = reshape([0.0_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.5_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk], [3, 3])
    has = [.false., .true., .false.]
    xb = 0
    xb(:,:,2) = reshape([0.0_rk, 0.0_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk, -1.0_rk, 0.5_rk, 1.0_rk], [3, 3])
    p(:,1) = [-0.005_rk, 0.3_rk, -0.02_rk]
    p(:,2) = [-0.01_rk, 0.3_rk, -0.02_rk]
    do k = 1, 2
      call triangle_projection(tri, p(:,k), n, dist, g)
      vf(k) = face_behind_surface(tri, n, dist, g, xb, has, p(:,k), 1.0e-3_rk)
    end do
    call check('face_behind_surface_of_a_triangle', all(vf == [behind_seam, behind_not]), &
               'verdicts '//trim(ints(vf))//' (2 0 wanted)')
    shares(:,1) = [.true., .false., .true.]
    xs1(:,:,1) = reshape([0.0_rk, 0.0_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk, 0.5_rk, 0.5_rk, -1.0_rk], [3, 3])
    p(:,1) = [0.3_rk, 0.5_rk, -0.8_rk]
    p(:,2) = [0.3_rk, 0.5_rk, -0.3_rk]
    do k = 1, 2
      call triangle_projection(tri, p(:,k), n, dist, g)
      bf(k) = face_beside_sharp_edge(tri, n, g, xs1, shares, 1, p(:,k), 1.0e-3_rk)
    end do
    call check('face_beside_sharp_edge_of_a_triangle', all(bf .eqv. [.true., .false.]), &
               'outside '//trim(logicals(bf))//' (TF wanted)')
    ! a segment: test_segment_seams' step, S = (2,0) -> (0,0) with the wall
    ! (0,0) -> (0,2) across its node 2: (-0.1,-0.3) in the seam (2),
    ! (-0.4,-0.3) beyond the gap (0)
    seg(:,1) = [2.0_rk, 0.0_rk, 0.0_rk]
    seg(:,2) = [0.0_rk, 0.0_rk, 0.0_rk]
    xb = 99.0_rk                             ! junk: the third corners and face
    xb(:,1:2,1) = reshape([0.0_rk, 0.0_rk, 0.0_rk, 0.0_rk, 2.0_rk, 0.0_rk], [3, 2])
    has = [.true., .false., .true.]          ! has(3): junk
    p(:,1) = [-0.1_rk, -0.3_rk, 0.0_rk]
    p(:,2) = [-0.4_rk, -0.3_rk, 0.0_rk]
    do k = 1, 2
      call face_projection(seg, p(:,k), n, dist, g)
      vf(k) = face_behind_surface(seg, n, dist, g, xb, has, p(:,k), 1.0e-3_rk)
    end do
    call check('face_behind_surface_of_a_segment_in_3d_layout', all(vf == [behind_seam, behind_not]), &
               'verdicts '//trim(ints(vf))//' (2 0 wanted)')
    ! test_segment_corners' 60-degree wedge: (0.2,-0.4) outside (T),
    ! (0.5,-0.2) inside (F); the side shares node 2, as the driver marks it
    ! ([1, 2, 3] /= 1; shares(3) and xs1's third corner ignored)
    shares(:,1) = [.false., .true., .true.]
    xs1 = 99.0_rk
    xs1(:,1:2,1) = reshape([0.0_rk, 0.0_rk, 0.0_rk, 1.0_rk, -sqrt(3.0_rk), 0.0_rk], [3, 2])
    p(:,1) = [0.2_rk, -0.4_rk, 0.0_rk]
    p(:,2) = [0.5_rk, -0.2_rk, 0.0_rk]
    do k = 1, 2
      call face_projection(seg, p(:,k), n, dist, g)
      bf(k) = face_beside_sharp_edge(seg, n, g, xs1, shares, 1, p(:,k), 1.0e-3_rk)
    end do
    call check('face_beside_sharp_edge_of_a_segment_in_3d_layout', all(bf .eqv. [.true., .false.]), &
               'outside '//trim(logicals(bf))//' (TF wanted)')
  end subroutine

  !> face_behind_surface of the point p behind segment xa's line.
  integer function verdict2(xa, xb, has, p)
    real(rk), intent(in) :: xa(3,2), xb(3,2,2), p(3)
    logical, intent(in) :: has(2)
    real(rk) :: n(3), dist, g(3)
    call face_projection(xa, p, n, dist, g)
    verdict2 = face_behind_surface(xa, n, dist, g, xb, has, p, 1.0e-3_rk)
  end function

  !> face_beside_sharp_edge of the point p behind segment xa's line.
  logical function outside2(xa, xb, shares, nb, p)
    real(rk), intent(in) :: xa(3,2), xb(3,2,1), p(3)
    logical, intent(in) :: shares(2,1)
    integer, intent(in) :: nb
    real(rk) :: n(3), dist, g(3)
    call face_projection(xa, p, n, dist, g)
    outside2 = face_beside_sharp_edge(xa, n, g, xb, shares, nb, p, 1.0e-3_rk)
  end function

  character(len=40) function ints(k)
    integer, intent(in) :: k(:)
    write(ints, '(6i2)') k
    ints = adjustl(ints)
  end function
end program test_segment2
