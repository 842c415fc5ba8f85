!> Unit test of the contact correction's iterations (udar_contact_kernels,
!> issue 13 item 1): four slave nodes strike one master triangle; the
!> passes of match_velocities over them, as contact_enforce makes them,
!> must converge to one answer whatever order the nodes are visited in:
!> every node either matched (its normal velocity equal to the master's at
!> its contact point) or separating with nothing received, momentum exact.
program test_contact_kernels
  use udar_kinds, only: rk
  use udar_config, only: contact_weights_area, contact_weights_distance
  use udar_vectors, only: cross
  use udar_contact_kernels, only: triangle_projection, master_shares, match_velocities, edge_crossing, edge_shares, &
                                  tetrahedron_coordinates, closest_on_triangle, behind_not, behind_face, &
                                  behind_seam, solve_normal_lcp, normal_rows_matrix, corner_angle, solve_friction_rows, row_components, &
                                  constrained_projection, return_on_planes
  use udar_contact_faces, only: face_behind_surface, face_beside_sharp_edge, seam_contact
  use udar_contact_model, only: interface_t, surface_neighbours, neighbour_across
  use unit_checks, only: check, check_summary, logicals
  use udar_vectors, only: tangent_basis
  implicit none
  integer, parameter :: ns = 4
  real(rk) :: xm(3,3), gs(3,ns), v_fwd(3,ns+3), v_rev(3,ns+3), dn_fwd(ns), dn_rev(ns), p0(3), worst, gap
  real(rk) :: one_pass(3,ns+3), ten_passes(3,ns+3)
  integer :: order(ns)
  character(len=200) :: detail
  ! test_friction_rows' pair of rows on one gap: nodes, masses, rows
  integer, parameter :: nn = 6
  real(rk) :: vp(3,nn), mp(nn), wp(0:3,2), cp(0:3,2), np(3,2), dnp(2), tp(3,2), mup(2)
  integer :: npn(0:3,2)
  ! master triangle in the plane z = 0, outward normal +z, at rest;
  ! slave nodes above it, at area coordinates gs, striking at 1 m/s
  xm = reshape([0.0_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk], [3, 3])
  gs = reshape([0.6_rk, 0.2_rk, 0.2_rk, 0.2_rk, 0.6_rk, 0.2_rk, 0.2_rk, 0.2_rk, 0.6_rk, &
                1.0_rk/3, 1.0_rk/3, 1.0_rk/3], [3, ns])
  order = [1, 2, 3, 4]
  call strike(order, 200, 0.0_rk, v_fwd, dn_fwd)
  order = [4, 3, 2, 1]
  call strike(order, 200, 0.0_rk, v_rev, dn_rev)
  worst = maxval(abs(v_fwd - v_rev))
  write(detail, '(a,es9.2,a)') 'largest velocity difference between the two orders ', worst, ' m/s (bound 1e-9)'
  call check('contact_order_independent', worst < 1.0e-9_rk, trim(detail))
  call check('contact_complementary', admissible(v_fwd, dn_fwd, gap) .and. admissible(v_rev, dn_rev, gap), &
             'every slave node matched or separating with nothing received; worst normal gap '//s(gap)//' m/s')
  p0 = 0.0_rk
  p0(3) = -real(ns, rk)
  worst = maxval(abs(sum(v_fwd, dim=2) - p0))
  call check('contact_momentum', worst < 1.0e-14_rk, 'total momentum change '//s(worst)//' N s (unit masses)')
  ! the passes do something: ten give a different (better) answer than one
  call strike([1, 2, 3, 4], 1, 0.0_rk, one_pass, dn_fwd)
  call strike([1, 2, 3, 4], 10, 0.0_rk, ten_passes, dn_fwd)
  call check('contact_passes_improve', maxval(abs(one_pass - ten_passes)) > 1.0e-3_rk .and. &
             maxval(abs(ten_passes - v_fwd)) < maxval(abs(one_pass - v_fwd)), &
             'one pass '//s(maxval(abs(one_pass - v_fwd)))//' m/s, ten '//s(maxval(abs(ten_passes - v_fwd)))// &
             ' m/s from the converged answer')
  ! with friction and a tangential approach: still one answer
  call strike([1, 2, 3, 4], 400, 0.3_rk, v_fwd, dn_fwd)
  call strike([4, 3, 2, 1], 400, 0.3_rk, v_rev, dn_rev)
  worst = maxval(abs(v_fwd - v_rev))
  write(detail, '(a,es9.2,a)') 'friction 0.3: largest velocity difference between the orders ', worst, ' m/s (bound 1e-9)'
  call check('contact_friction_order_independent', worst < 1.0e-9_rk, trim(detail))
  call test_normal_lcp()
  call test_friction_rows()
  call test_single_correction()
  call test_moving_correction()
  call test_moving_edges()
  call test_edges_and_elements()
  call test_seams()
  call test_seam_on_plane()
  call test_matching_on_plane()
  call test_sharp_edges()
  call test_beyond_face_beside()
  call check_summary()
contains

  !> A slave node on the symmetry plane y = 0 strikes a face that leans
  !> out of the plane (normal (0, 0.6, 1)/|.|; its nodes 1 and 2 on the
  !> plane too), by hand: matched with the planes' projections
  !> (match_velocities with proj), no node on the plane moves out of it, the
  !> normal velocities are equal afterwards, and momentum in the plane is
  !> exact. Matched without them and the velocity conditions applied
  !> afterwards (before 0.9.18), the node still approaches the face at a
  !> quarter of its speed. Off the planes (identity projections) it is
  !> match_velocities' frictionless change; two planes leave a line. Its
  !> return to the face's plane along the plane (return_on_planes) ends on
  !> it; the part the velocity conditions keep of the return does not.
  subroutine test_matching_on_plane()
    real(rk) :: xa(3,3), xs(3), n(3), dist, g(3), gc(3), share(3), vm(3,3), vs(3), dvs(3), dvm(3,3), dn, dtv(3)
    real(rk) :: proj(3,3,0:3), planes(4,2), rate, mom(3), dvs0(3), dvm0(3,3), dn0, line(3), w(3)
    real(rk), parameter :: ms = 0.7_rk, mm(3) = [1.3_rk, 0.6_rk, 2.1_rk]
    logical :: acted
    integer :: a
    xa = reshape([0.0_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk, 0.0_rk, 0.0_rk, 1.0_rk, -0.6_rk], [3, 3])
    planes(:,1) = [0.0_rk, 1.0_rk, 0.0_rk, 0.0_rk]
    planes(:,2) = [1.0_rk, 1.0_rk, 0.0_rk, 0.0_rk]/sqrt(2.0_rk)
    xs = [0.5_rk, 0.0_rk, -0.01_rk]
    call triangle_projection(xa, xs, n, dist, g)
    call check('plane_case_leans', abs(n(2)) > 0.5_rk .and. dist < 0.0_rk .and. all(g > 0.0_rk), &
               'normal y '//s(n(2))//', behind by '//s(-dist)//', inside the face')
    gc = g
    call master_shares(contact_weights_area, xa, xs, g, n, xa, xs, share)
    vm = 0.0_rk
    vs = [0.0_rk, 0.0_rk, -2.0_rk]
    proj(:,:,0) = constrained_projection(1, planes(:,1:1))
    proj(:,:,1) = proj(:,:,0)
    proj(:,:,2) = proj(:,:,0)
    proj(:,:,3) = constrained_projection(0, planes(:,1:1))
    call match_velocities(n, ms, vs, mm, vm, g, share, 0.0_rk, 0.0_rk, [0.0_rk, 0.0_rk, 0.0_rk], dvs, dvm, acted, dn, dtv, proj=proj)
    rate = dot_product(n, vs + dvs - (gc(1)*dvm(:,1) + gc(2)*dvm(:,2) + gc(3)*dvm(:,3)))
    call check('plane_matching_stays_in_plane', acted .and. dvs(2) == 0.0_rk .and. dvm(2,1) == 0.0_rk .and. &
               dvm(2,2) == 0.0_rk .and. dvm(2,3) /= 0.0_rk, &
               'y changes of the plane nodes '//s(dvs(2))//' '//s(dvm(2,1))//' '//s(dvm(2,2)))
    call check('plane_matching_matched', abs(rate) < 1.0e-14_rk, 'normal rate after '//s(rate)//' m/s')
    mom = ms*dvs + mm(1)*dvm(:,1) + mm(2)*dvm(:,2) + mm(3)*dvm(:,3)
    call check('plane_matching_momentum_in_plane', abs(mom(1)) < 1.0e-15_rk .and. abs(mom(3)) < 1.0e-15_rk, &
               'momentum change x '//s(mom(1))//', z '//s(mom(3))//' N s')
    ! without the projections, the velocity conditions applied afterwards
    call match_velocities(n, ms, vs, mm, vm, g, share, 0.0_rk, 0.0_rk, [0.0_rk, 0.0_rk, 0.0_rk], &
                          dvs0, dvm0, acted, dn0, dtv)
    dvs0(2) = 0.0_rk
    dvm0(2,1:2) = 0.0_rk
    rate = dot_product(n, vs + dvs0 - (gc(1)*dvm0(:,1) + gc(2)*dvm0(:,2) + gc(3)*dvm0(:,3)))
    call check('plane_matching_unprojected_leaves_approach', rate < -0.3_rk, &
               'matched unprojected, then held to the plane: normal rate '//s(rate)//' m/s')
    ! off the planes: match_velocities' frictionless change
    do a = 0, 3
      proj(:,:,a) = constrained_projection(0, planes)
    end do
    call match_velocities(n, ms, vs, mm, vm, g, share, 0.0_rk, 0.0_rk, [0.0_rk, 0.0_rk, 0.0_rk], &
                          dvs0, dvm0, acted, dn0, dtv)
    call match_velocities(n, ms, vs, mm, vm, g, share, 0.0_rk, 0.0_rk, [0.0_rk, 0.0_rk, 0.0_rk], dvs, dvm, acted, dn, dtv, proj=proj)
    call check('plane_matching_identity', maxval(abs(dvs - dvs0)) < 1.0e-15_rk .and. maxval(abs(dvm - dvm0)) < 1.0e-15_rk &
               .and. abs(dn - dn0) < 1.0e-15_rk, 'off the planes as before')
    ! with proj the change is the normal one alone: friction is not taken
    call match_velocities(n, ms, vs + [0.5_rk, 0.0_rk, 0.0_rk], mm, vm, g, share, 0.3_rk, 0.0_rk, [0.0_rk, 0.0_rk, 0.0_rk], &
                          dvs, dvm, acted, dn, dtv, proj=proj)
    call check('plane_matching_frictionless', acted .and. all(dtv == 0.0_rk) .and. abs(dn - dn0) < 1.0e-15_rk, &
               'friction 0.3, sliding at 0.5 m/s: tangential change '//s(norm2(dtv)))
    ! a separating node is released; one already pushed is taken back only to zero
    call match_velocities(n, ms, -vs, mm, vm, g, share, 0.0_rk, 0.0_rk, [0.0_rk, 0.0_rk, 0.0_rk], dvs, dvm, acted, dn, dtv, proj=proj)
    call check('plane_matching_releases', .not. acted .and. dn == 0.0_rk, 'separating: dn '//s(dn))
    call match_velocities(n, ms, -vs, mm, vm, g, share, 0.0_rk, 0.25_rk, [0.0_rk, 0.0_rk, 0.0_rk], dvs, dvm, acted, dn, dtv, proj=proj)
    call check('plane_matching_takes_back_to_zero', acted .and. dn == -0.25_rk, 'pushed before by 0.25: dn '//s(dn))
    ! the node's return to the face's plane (-dist n) along the plane y = 0
    ! puts it on the face's plane; the velocity conditions' part of it alone
    ! leaves it behind
    w = return_on_planes(-dist*n, constrained_projection(1, planes(:,1:1)))
    call check('plane_return_onto_the_face', w(2) == 0.0_rk .and. abs(dot_product(n, xs + w - xa(:,1))) < 1.0e-16_rk &
               .and. dot_product(n, xs + matmul(constrained_projection(1, planes(:,1:1)), -dist*n) - xa(:,1)) < -1.0e-3_rk, &
               'returned along the plane: left behind by '//s(-dot_product(n, xs + w - xa(:,1)))//' m')
    ! a face within 30 degrees of lying in the plane, every node on it: left
    ! alone (matched, the node would be sent along the plane at 3 times
    ! its approach)
    do a = 0, 3
      proj(:,:,a) = constrained_projection(1, planes(:,1:1))
    end do
    call match_velocities([0.0_rk, 0.95_rk, sqrt(1.0_rk - 0.95_rk**2)], ms, vs, mm, vm, g, share, 0.0_rk, 0.0_rk, &
                          [0.0_rk, 0.0_rk, 0.0_rk], dvs, dvm, acted, dn, dtv, proj=proj)
    call check('plane_matching_leaves_a_face_near_the_plane', .not. acted .and. all(dvs == 0.0_rk), &
               'normal 18 degrees out of the plane: dn '//s(dn))
    ! two planes (y = 0 and x = -y): a node on both moves along z alone
    line = matmul(constrained_projection(3, planes), [1.0_rk, 2.0_rk, 3.0_rk])
    call check('plane_projection_two_planes', maxval(abs(line - [0.0_rk, 0.0_rk, 3.0_rk])) < 1.0e-15_rk, &
               'projected (1, 2, 3): '//s(line(1))//' '//s(line(2))//' '//s(line(3)))
  end subroutine

  !> corner_angle by hand, and the angle-weighted normal of a cube's corner
  !> (the leave-the-body test of contact_driver's returns): its three faces
  !> cut into five triangles at the corner (two of 45 degrees on x = 0 and
  !> on y = 0, one of 90 on z = 0) give the diagonal direction, as the
  !> faces' equal angles do; the plain sum of the five normals does not.
  subroutine test_corner_normal()
    real(rk) :: o(3), ex(3), ey(3), ez(3), d(3), xa(3,3), wn(3), plain(3), n(3), dist, g(3), err
    integer :: k
    o = 0.0_rk
    ex = [1.0_rk, 0.0_rk, 0.0_rk]; ey = [0.0_rk, 1.0_rk, 0.0_rk]; ez = [0.0_rk, 0.0_rk, 1.0_rk]
    xa = reshape([o, ex, [0.5_rk, sqrt(0.75_rk), 0.0_rk]], [3, 3])
    err = abs(corner_angle(xa, 1) - acos(-1.0_rk)/3) + abs(corner_angle(xa, 3) - acos(-1.0_rk)/3)
    xa = reshape([o, ex, ey], [3, 3])
    err = err + abs(corner_angle(xa, 1) - acos(-1.0_rk)/2) + abs(corner_angle(xa, 2) - acos(-1.0_rk)/4)
    call check('corner_angle_by_hand', err < 1.0e-15_rk, 'summed error '//s(err))
    ! the solid x, y, z >= 0: outward normals -x, -y, -z (counter-clockwise seen from outside)
    wn = 0.0_rk
    plain = 0.0_rk
    do k = 1, 5
      select case (k)
      case (1); d = ey + ez; xa = reshape([o, d, ey], [3, 3])     ! x = 0, two halves
      case (2); xa = reshape([o, ez, d], [3, 3])
      case (3); d = ex + ez; xa = reshape([o, ex, d], [3, 3])     ! y = 0, two halves
      case (4); xa = reshape([o, d, ez], [3, 3])
      case (5); xa = reshape([o, ey, ex], [3, 3])                 ! z = 0, one triangle
      end select
      call triangle_projection(xa, [0.1_rk, 0.1_rk, 0.1_rk], n, dist, g)
      wn = wn + corner_angle(xa, 1)*n
      plain = plain + n
    end do
    err = maxval(abs(wn/norm2(wn) + [1.0_rk, 1.0_rk, 1.0_rk]/sqrt(3.0_rk)))
    call check('corner_normal_of_a_cube', err < 1.0e-15_rk .and. maxval(abs(plain/norm2(plain) &
               + [1.0_rk, 1.0_rk, 1.0_rk]/sqrt(3.0_rk))) > 0.05_rk, 'angle-weighted off the diagonal by '//s(err))
  end subroutine

  !> The surface beyond a triangle's edges (face_behind_surface,
  !> closest_on_triangle, neighbour_across), by hand. Triangle T =
  !> (0,0,0), (1,0.5,0), (0,1,0) in the plane z = 0, outward +z; the edge
  !> opposite its corner 2 is x = 0. Across it a concave neighbour rising at
  !> 45 degrees (to (-1,0.5,1): a dented surface; the gap between the two
  !> outlines is tan(22.5) = 0.414 of a node's depth wide), a shallow one
  !> (to (-1,0.5,0.1): 0.0499 of the depth), or a convex one (falling back
  !> under T to (0.5,0.5,-1)).
  subroutine test_seams()
    real(rk) :: xa(3,3), xb(3,3,3), g(3), c(3), err
    integer :: nbr(3,7), t, a
    real(rk) :: x0(3,11)
    real(rk), parameter :: wedge_deg(4) = [0.0_rk, 60.0_rk, 180.0_rk, 240.0_rk]   ! nodes 8..11
    logical :: has(3)
    integer :: v(6)
    type(interface_t) :: it
    xa = reshape([0.0_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.5_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk], [3, 3])
    has = [.false., .true., .false.]
    xb = 0
    xb(:,:,2) = reshape([0.0_rk, 0.0_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk, -1.0_rk, 0.5_rk, 1.0_rk], [3, 3])
    ! 0.02 deep, 0.005 beyond the edge (gap 0.0083): in the seam; 0.01 beyond: the neighbour's
    v(1) = verdict_at(xa, xb, has, [-0.005_rk, 0.3_rk, -0.02_rk])
    v(2) = verdict_at(xa, xb, has, [-0.01_rk, 0.3_rk, -0.02_rk])
    ! without the neighbour (a rim): off the triangle
    has(2) = .false.
    v(3) = verdict_at(xa, xb, has, [-0.005_rk, 0.3_rk, -0.02_rk])
    has(2) = .true.
    ! the shallow fold: 0.01 beyond at 0.3 deep (gap 0.0150) in the seam, at 0.1 deep (0.0050) not
    xb(:,:,2) = reshape([0.0_rk, 0.0_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk, -1.0_rk, 0.5_rk, 0.1_rk], [3, 3])
    v(4) = verdict_at(xa, xb, has, [-0.01_rk, 0.3_rk, -0.3_rk])
    v(5) = verdict_at(xa, xb, has, [-0.01_rk, 0.3_rk, -0.1_rk])
    ! beyond a convex edge: not behind T
    xb(:,:,2) = reshape([0.0_rk, 0.0_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk, 0.5_rk, 0.5_rk, -1.0_rk], [3, 3])
    v(6) = verdict_at(xa, xb, has, [-0.01_rk, 0.5_rk, -0.002_rk])
    call check('seam_verdicts_by_hand', all(v == [behind_seam, behind_not, behind_not, behind_seam, behind_not, behind_not]), &
               'concave: in the gap / beyond it / rim; shallow: deep / not deep enough; convex (2 0 0 2 0 0 wanted): '// &
               trim(ints(v)))
    ! on the triangle behind its plane: the face
    has = .true.
    call check('seam_verdict_on_the_face', verdict_at(xa, xb, has, [0.2_rk, 0.5_rk, -0.3_rk]) == behind_face, 'a projection on T')
    ! closest points: on the edge x = 0, at a corner, the projection
    call closest_on_triangle(xa, [-0.5_rk, 0.5_rk, 0.3_rk], c, g)
    err = maxval(abs(c - [0.0_rk, 0.5_rk, 0.0_rk])) + maxval(abs(g - [0.5_rk, 0.0_rk, 0.5_rk]))
    call closest_on_triangle(xa, [-1.0_rk, -1.0_rk, 0.0_rk], c, g)
    err = err + maxval(abs(c)) + maxval(abs(g - [1.0_rk, 0.0_rk, 0.0_rk]))
    call closest_on_triangle(xa, [0.2_rk, 0.5_rk, -1.0_rk], c, g)
    err = err + maxval(abs(c - [0.2_rk, 0.5_rk, 0.0_rk])) + maxval(abs(g - [0.4_rk, 0.2_rk, 0.4_rk]))
    call check('closest_on_triangle_by_hand', err < 1.0e-15_rk, 'summed error '//s(err))
    call test_corner_normal()
    ! neighbours of a strip of three triangles (nodes 1..5) and of two
    ! wedges touching along the edge 6-7 only (z from 0 to 1; faces to
    ! nodes 8..11 at 0, 60, 180, 240 degrees about it, each wedge's faces
    ! oriented outward): across an edge of four faces, the one of the same
    ! wedge (the face at 0 degrees has two faces running the edge back,
    ! at 60 and 240 degrees; the turn into its body meets 60 first)
    it%tri = reshape([1, 2, 3, 3, 2, 4, 3, 4, 5, 7, 6, 8, 6, 7, 11, 7, 6, 10, 6, 7, 9], [3, 7])
    x0 = 0
    x0(:,7) = [0.0_rk, 0.0_rk, 1.0_rk]
    do t = 8, 11
      x0(:,t) = [cos(wedge_deg(t-7)*acos(-1.0_rk)/180), sin(wedge_deg(t-7)*acos(-1.0_rk)/180), 0.5_rk]
    end do
    call surface_neighbours(it, x0)
    do t = 1, 7
      do a = 1, 3
        nbr(a,t) = neighbour_across(it, t, a)
      end do
    end do
    call check('neighbour_across_by_hand', all(nbr(:,1) == [2, 0, 0]) .and. all(nbr(:,2) == [0, 3, 1]) &
               .and. all(nbr(:,3) == [0, 0, 2]) .and. all(nbr(:,4) == [0, 0, 7]) .and. all(nbr(:,5) == [0, 0, 6]) &
               .and. all(nbr(:,6) == [0, 0, 5]) .and. all(nbr(:,7) == [0, 0, 4]), &
               'a strip and two wedges on one edge, 0 0 7 / 0 0 6 / 0 0 5 / 0 0 4 wanted for the wedges: '// &
               ints(nbr(3,4:7)))
  end subroutine

  !> The seam's contact (seam_contact) of a node on the symmetry plane y = 0,
  !> by hand. Triangle (0,0,0), (-0.5,0.4,1), (1,0,0): its edge along x on
  !> the plane, leaning out of it (outward normal (0, 0.928, -0.371)). The
  !> node (-0.3,0,0.4) is 0.149 behind its plane, beyond both its edge on
  !> the plane and the edge to (-0.5,0.4,1), whose point at 0.55/1.41 of
  !> the way is the closest, 0.188 away and off the plane. With a search
  !> depth of 0.16 the node is taken off the plane (the way to the point, the
  !> direction out of the body), and not on it: there only the in-plane part
  !> of the move would stay, and the node would go 0.105 along x, not to the
  !> face (the Fig. 4 deck's free plate nodes sent 0.34-0.70 mm into the
  !> rod, theory.md 11).
  subroutine test_seam_on_plane()
    real(rk) :: xa(3,3), xs(3), c(3), g(3), n(3), dist, c_hand(3), err, dist_plane, n_plane(3), g_plane(3)
    logical :: off_taken, on_taken
    xa = reshape([0.0_rk, 0.0_rk, 0.0_rk, -0.5_rk, 0.4_rk, 1.0_rk, 1.0_rk, 0.0_rk, 0.0_rk], [3, 3])
    xs = [-0.3_rk, 0.0_rk, 0.4_rk]
    call triangle_projection(xa, xs, n_plane, dist_plane, g_plane)
    c_hand = (0.55_rk/1.41_rk)*xa(:,2)
    call seam_contact(xa, xs, 0.16_rk, .false., c, g, n, dist, off_taken)
    err = maxval(abs(c - c_hand)) + abs(dist + norm2(c_hand - xs)) + maxval(abs(n - (c_hand - xs)/norm2(c_hand - xs)))
    call check('seam_contact_by_hand', off_taken .and. err < 1.0e-15_rk .and. abs(dist_plane + 0.4_rk*0.4_rk/sqrt(1.16_rk)) &
               < 1.0e-15_rk .and. minval(g_plane) < 0.0_rk, 'off the plane: taken '//trim(logicals([off_taken]))// &
               ', summed error '//s(err)//', plane depth '//s(-dist_plane)//', closest point '//s(-dist)//' away')
    call seam_contact(xa, xs, 0.16_rk, .true., c, g, n, dist, on_taken)
    call check('seam_contact_on_a_symmetry_plane_held_to_the_depth', .not. on_taken, &
               'on the plane, the closest point '//s(-dist)//' away beyond the search depth 0.16: taken '// &
               trim(logicals([on_taken]))//' (F wanted)')
  end subroutine

  !> A node behind triangle T (that of test_seams: z = 0, outward +z, the
  !> edge x = 0 opposite its corner 2) beside a sharp convex edge
  !> (face_beside_sharp_edge), by hand. Across x = 0 (sharing T's corners 1 and
  !> 3) a face falling under T to (0.5,0.5,-1): the interior angle is
  !> atan(2) = 63.4 degrees, the body between the planes z = 0 and
  !> 2x + z = 0. Points with their projection on T: (0.3,0.5,-0.8) is in
  !> front of that face (2x + z = -0.2) with its projection on it: outside;
  !> (0.3,0.5,-0.3) is inside the body; (0.6,0.5,-1.5) is in front of the
  !> face's plane but projects beyond its apex: not judged outside;
  !> (0.25,0.5,-0.5) lies on the face's plane: outside (a node on the face
  !> beside). The same face sharing only T's corner 1 (a sharp corner):
  !> (0.3,0.5,-0.8) outside. With the face at 90 degrees (down to
  !> (0,0.5,-1)) a node on its plane projects onto T's edge: not outside (it
  !> crossed the top face); no face beside, or a rising one: not outside.
  subroutine test_sharp_edges()
    real(rk) :: xa(3,3), xb(3,3,1)
    logical :: edge(3,1), corner(3,1), v(9)
    xa = reshape([0.0_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.5_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk], [3, 3])
    edge(:,1) = [.true., .false., .true.]
    corner(:,1) = [.true., .false., .false.]
    xb(:,:,1) = reshape([0.0_rk, 0.0_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk, 0.5_rk, 0.5_rk, -1.0_rk], [3, 3])
    v(1) = outside_at(xa, xb, edge, 1, [0.3_rk, 0.5_rk, -0.8_rk])
    v(2) = outside_at(xa, xb, edge, 1, [0.3_rk, 0.5_rk, -0.3_rk])
    v(3) = outside_at(xa, xb, edge, 1, [0.6_rk, 0.5_rk, -1.5_rk])
    v(4) = outside_at(xa, xb, edge, 1, [0.25_rk, 0.5_rk, -0.5_rk])
    v(5) = outside_at(xa, xb, corner, 1, [0.3_rk, 0.5_rk, -0.8_rk])
    v(6) = outside_at(xa, xb, edge, 0, [0.3_rk, 0.5_rk, -0.8_rk])
    xb(:,:,1) = reshape([0.0_rk, 0.0_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk, 0.0_rk, 0.5_rk, -1.0_rk], [3, 3])
    v(7) = outside_at(xa, xb, edge, 1, [0.0_rk, 0.5_rk, -0.3_rk])
    v(8) = outside_at(xa, xb, edge, 1, [0.1_rk, 0.5_rk, -0.3_rk])
    xb(:,:,1) = reshape([0.0_rk, 0.0_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk, -1.0_rk, 0.5_rk, 1.0_rk], [3, 3])
    v(9) = outside_at(xa, xb, edge, 1, [0.3_rk, 0.5_rk, -0.8_rk])
    call check('sharp_edge_verdicts_by_hand', all(v .eqv. [.true., .false., .false., .true., .true., .false., .false., &
               .false., .false.]), 'in front / inside / beyond the apex / on the plane / corner / none / square edge (2) '// &
               '/ rising, TFFTTFFFF wanted: '//logicals(v))
  end subroutine

  !> The node of test_sharp_edges that is in front of the face beside B
  !> ((0,0,0), (0,1,0), (0.5,0.5,-1)) but projects beyond its apex,
  !> p = (0.6,0.5,-1.5) (area coordinates on B -0.22, -0.22, 1.44: past
  !> both edges at the apex), with the faces across those two edges given
  !> (face_beside_sharp_edge's xc, hasc), by hand: faces to q = (1,0.5,-1.5)
  !> fall away behind B's plane (centroids 0.075 behind: a knife edge),
  !> so p is outside; faces to (0,0.5,-2) rise (0.30 in front: a
  !> valley) with p 0.153 behind them: not outside; faces to (1,0.5,-3)
  !> rise with p 0.022 in front of them: outside; none known: not outside,
  !> as without them.
  subroutine test_beyond_face_beside()
    real(rk) :: xa(3,3), xb(3,3,1), xc(3,3,3,1), b1(3), b2(3), b3(3), p(3), n(3), dist, g(3), q(3,3)
    logical :: edge(3,1), hasc(3,1), v(4)
    integer :: k
    xa = reshape([0.0_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.5_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk], [3, 3])
    edge(:,1) = [.true., .false., .true.]
    b1 = [0.0_rk, 0.0_rk, 0.0_rk]; b2 = [0.0_rk, 1.0_rk, 0.0_rk]; b3 = [0.5_rk, 0.5_rk, -1.0_rk]
    xb(:,:,1) = reshape([b1, b2, b3], [3, 3])
    p = [0.6_rk, 0.5_rk, -1.5_rk]
    q = reshape([1.0_rk, 0.5_rk, -1.5_rk, 0.0_rk, 0.5_rk, -2.0_rk, 1.0_rk, 0.5_rk, -3.0_rk], [3, 3])
    call triangle_projection(xa, p, n, dist, g)
    hasc(:,1) = [.true., .true., .false.]
    do k = 1, 3
      xc = 0
      xc(:,:,1,1) = reshape([b3, b2, q(:,k)], [3, 3])     ! across B's edge opposite its corner 1
      xc(:,:,2,1) = reshape([b1, b3, q(:,k)], [3, 3])     ! opposite its corner 2
      v(k) = face_beside_sharp_edge(xa, n, g, xb, edge, 1, p, 1.0e-3_rk, xc, hasc)
    end do
    v(4) = face_beside_sharp_edge(xa, n, g, xb, edge, 1, p, 1.0e-3_rk, xc, spread(spread(.false., 1, 3), 2, 1))
    call check('beyond_face_beside_verdicts_by_hand', all(v .eqv. [.true., .false., .true., .false.]), &
               'knife edge / valley, behind / valley, in front / none known, TFTF wanted: '//logicals(v))
  end subroutine

  logical function outside_at(xa, xb, shares, nb, p)
    real(rk), intent(in) :: xa(3,3), xb(3,3,1), p(3)
    logical, intent(in) :: shares(3,1)
    integer, intent(in) :: nb
    real(rk) :: n(3), dist, g(3)
    call triangle_projection(xa, p, n, dist, g)
    outside_at = face_beside_sharp_edge(xa, n, g, xb, shares, nb, p, 1.0e-3_rk)
  end function

  !> face_behind_surface of the point p behind triangle xa's plane.
  integer function verdict_at(xa, xb, has, p)
    real(rk), intent(in) :: xa(3,3), xb(3,3,3), p(3)
    logical, intent(in) :: has(3)
    real(rk) :: n(3), dist, g(3)
    call triangle_projection(xa, p, n, dist, g)
    verdict_at = face_behind_surface(xa, n, dist, g, xb, has, p, 1.0e-3_rk)
  end function

  character(len=40) function ints(k)
    integer, intent(in) :: k(:)
    write(ints, '(6i2)') k
  end function

  !> Edge against edge and a point in the element under a face, by hand:
  !> slave edge (-1,0,0.2)-(1,0,0.2) moving at (0,0,-2) for 0.2 s over the
  !> resting master edge (0,-1,0)-(0,1,0): its end position
  !> (-1,0,-0.2)-(1,0,-0.2) crosses the master edge at alpha = beta = 1/2
  !> (g1 = -0.2 along n = +z), where it was 0.2 above it (g0 = 0.2).
  !> The parallel pair and a pair that closes but does not cross are not
  !> crossings. The point (0.2, 0.2, -0.3) under the face z = 0 of the
  !> tetrahedron with fourth corner (0,0,-1): coordinates (0.3, 0.2, 0.2,
  !> 0.3).
  subroutine test_edges_and_elements()
    real(rk) :: alpha, beta, n(3), g0, g1, lam(4), xa(3,3)
    real(rk), parameter :: z3(3) = 0.0_rk, vdown(3) = [0.0_rk, 0.0_rk, -2.0_rk]
    logical :: crossed, parallel, missed
    call edge_crossing([-1.0_rk, 0.0_rk, -0.2_rk], [1.0_rk, 0.0_rk, -0.2_rk], [0.0_rk, -1.0_rk, 0.0_rk], &
                       [0.0_rk, 1.0_rk, 0.0_rk], vdown, vdown, z3, z3, 0.2_rk, alpha, beta, n, g0, g1, crossed)
    call check('edge_crossing_by_hand', crossed .and. abs(alpha - 0.5_rk) < 1e-15_rk .and. &
               abs(beta - 0.5_rk) < 1e-15_rk .and. abs(n(3) - 1.0_rk) < 1e-15_rk .and. &
               abs(g1 + 0.2_rk) < 1e-15_rk .and. abs(g0 - 0.2_rk) < 1e-15_rk .and. abs(n(1)) + abs(n(2)) == 0.0_rk, &
               'alpha '//s(alpha)//', beta '//s(beta)//', g0 '//s(g0)//', g1 '//s(g1)//', n_z '//s(n(3)))
    call edge_crossing([0.0_rk, -1.0_rk, -0.1_rk], [0.0_rk, 1.0_rk, -0.1_rk], [0.0_rk, -1.0_rk, 0.0_rk], &
                       [0.0_rk, 1.0_rk, 0.0_rk], vdown, vdown, z3, z3, 0.2_rk, alpha, beta, n, g0, g1, parallel)
    call edge_crossing([-1.0_rk, 0.0_rk, 0.1_rk], [1.0_rk, 0.0_rk, 0.3_rk], [0.0_rk, -1.0_rk, 0.0_rk], &
                       [0.0_rk, 1.0_rk, 0.0_rk], vdown/10, vdown/10, z3, z3, 0.2_rk, alpha, beta, n, g0, g1, missed)
    call check('edge_crossing_parallel_and_short_of_it', .not. parallel .and. .not. missed, &
               'parallel edges and edges 0.04 apart after the step are no crossing')
    xa = reshape([0.0_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk], [3, 3])
    call tetrahedron_coordinates(xa, [0.0_rk, 0.0_rk, -1.0_rk], [0.2_rk, 0.2_rk, -0.3_rk], lam)
    call check('tetrahedron_coordinates_by_hand', maxval(abs(lam - [0.3_rk, 0.2_rk, 0.2_rk, 0.3_rk])) < 1e-15_rk, &
               'lambda '//s(lam(1))//' '//s(lam(2))//' '//s(lam(3))//' '//s(lam(4)))
  end subroutine
  !> One slave node against one master triangle, a frictionless push:
  !> momentum is exact with either shares; the angular momentum about the
  !> origin changes by (x_s - sum R_a x_a) x J, which is zero with area
  !> shares (sum g_a x_a is the projection of x_s, and J is along n) and
  !> not with the paper's distance shares; and at an edge's midpoint the
  !> area shares give nothing to the opposite node.
  subroutine test_single_correction()
    real(rk) :: xa(3,3), xs(3), n(3), dist, g(3), share(3), vm(3,3), dvs(3), dvm(3,3), dn, dtv(3)
    real(rk) :: dl(3), scale
    real(rk), parameter :: ms = 0.7_rk, mm(3) = [1.3_rk, 0.6_rk, 2.1_rk]
    logical :: acted
    integer :: w, a
    character(len=8), parameter :: names(2) = ['area    ', 'distance']
    real(rk) :: moment_error(2)
    xa = reshape([0.1_rk, -0.2_rk, 0.05_rk, 1.4_rk, 0.1_rk, -0.1_rk, 0.3_rk, 1.1_rk, 0.2_rk], [3, 3])
    xs = 0.2_rk*xa(:,1) + 0.5_rk*xa(:,2) + 0.3_rk*xa(:,3)
    call triangle_projection(xa, xs, n, dist, g)
    xs = xs - 1.0e-3_rk*n                     ! 1 mm behind the face
    call triangle_projection(xa, xs, n, dist, g)
    vm = 0.0_rk
    do w = 1, 2
      call master_shares(merge(contact_weights_area, contact_weights_distance, w == 1), xa, xs, g, n, xa, xs, share)
      call match_velocities(n, ms, -2.0_rk*n, mm, vm, g, share, 0.0_rk, 0.0_rk, [0.0_rk, 0.0_rk, 0.0_rk], &
                            dvs, dvm, acted, dn, dtv)
      dl = ms*cross(xs, dvs)
      do a = 1, 3
        dl = dl + mm(a)*cross(xa(:,a), dvm(:,a))
      end do
      scale = ms*dn*maxval(abs(xa))
      moment_error(w) = norm2(dl)/scale
      call check('single_correction_momentum_'//trim(names(w)), &
                 norm2(ms*dvs + mm(1)*dvm(:,1) + mm(2)*dvm(:,2) + mm(3)*dvm(:,3)) < 1.0e-15_rk*ms*dn, &
                 'ms dvs + sum ma dva = 0 with '//trim(names(w))//' shares')
    end do
    call check('single_correction_angular_momentum_area', moment_error(1) < 1.0e-14_rk, &
               'angular momentum change '//s(moment_error(1))//' of ms dv_N |x| with area shares')
    call check('single_correction_angular_momentum_distance', moment_error(2) > 1.0e-3_rk, &
               'angular momentum change '//s(moment_error(2))//' of ms dv_N |x| with the paper''s distance shares'// &
               ' (not a moment balance)')
    ! a contact at the midpoint of edge 1-2: area shares 1/2, 1/2, 0
    xs = 0.5_rk*(xa(:,1) + xa(:,2)) - 1.0e-3_rk*n
    call triangle_projection(xa, xs, n, dist, g)
    call master_shares(contact_weights_area, xa, xs, g, n, xa, xs, share)
    call check('edge_midpoint_area_shares', abs(share(3)) < 1.0e-12_rk .and. abs(share(1) - 0.5_rk) < 1.0e-12_rk, &
               'opposite node '//s(share(3))//', edge nodes '//s(share(1))//' '//s(share(2)))
    call master_shares(contact_weights_distance, xa, xs, g, n, xa, xs, share)
    call check('edge_midpoint_distance_shares', share(3) > 0.1_rk, &
               'the paper''s shares give the opposite node '//s(share(3)))
  end subroutine

  !> The same push over a step dt in which the nodes move (the slave node
  !> sliding 40 m/s across a turning triangle): the leapfrog conserves
  !> sum m x(n) x v(n+1/2), so a correction must exert no moment about
  !> the positions at the start of the step, x - dt v. The area shares of
  !> the start position projected along n do; the area coordinates at the
  !> end of the step (0.5.3) do not.
  subroutine test_moving_correction()
    real(rk) :: xa(3,3), xs(3), va(3,3), vs(3), xa0(3,3), xs0(3), n(3), dist, g(3), share(3), dvs(3), dvm(3,3)
    real(rk) :: dn, dtv(3), dl(3), moment(2), sum_w
    real(rk), parameter :: ms = 0.7_rk, mm(3) = [1.3_rk, 0.6_rk, 2.1_rk], dt = 2.0e-4_rk
    logical :: acted
    integer :: w, a
    xa = reshape([0.1_rk, -0.2_rk, 0.05_rk, 1.4_rk, 0.1_rk, -0.1_rk, 0.3_rk, 1.1_rk, 0.2_rk], [3, 3])
    va = reshape([3.0_rk, -1.0_rk, 2.0_rk, -2.0_rk, 4.0_rk, 1.0_rk, 1.0_rk, 2.0_rk, -5.0_rk], [3, 3])
    xs = 0.2_rk*xa(:,1) + 0.5_rk*xa(:,2) + 0.3_rk*xa(:,3)
    call triangle_projection(xa, xs, n, dist, g)
    xs = xs - 1.0e-3_rk*n
    vs = 40.0_rk*(xa(:,2) - xa(:,1))/norm2(xa(:,2) - xa(:,1)) - 5.0_rk*n
    call triangle_projection(xa, xs, n, dist, g)
    xs0 = xs - dt*vs
    do a = 1, 3
      xa0(:,a) = xa(:,a) - dt*va(:,a)
    end do
    do w = 1, 2
      if (w == 1) then
        call master_shares(contact_weights_area, xa, xs, g, n, xa0, xs0, share)
        sum_w = sum(share)
      else
        share = g
      end if
      call match_velocities(n, ms, vs, mm, va, g, share, 0.0_rk, 0.0_rk, [0.0_rk, 0.0_rk, 0.0_rk], &
                            dvs, dvm, acted, dn, dtv)
      dl = ms*cross(xs0, dvs)
      do a = 1, 3
        dl = dl + mm(a)*cross(xa0(:,a), dvm(:,a))
      end do
      moment(w) = norm2(dl)/(ms*dn*maxval(abs(xa)))
    end do
    call check('moving_correction_angular_momentum_start_shares', moment(1) < 1.0e-14_rk .and. &
               abs(sum_w - 1.0_rk) < 1.0e-15_rk, 'moment about the start positions '//s(moment(1))// &
               ' of ms dv_N |x| with the start-of-step area shares (sum '//s(sum_w)//')')
    call check('moving_correction_angular_momentum_end_shares', moment(2) > 1.0e-5_rk, &
               'moment '//s(moment(2))//' of ms dv_N |x| with the end-of-step area coordinates')
  end subroutine

  !> An edge-to-edge impulse between edges that slide and turn over the
  !> step: shared by edge_shares, no moment about the start positions;
  !> shared by the end's closest points, a moment.
  subroutine test_moving_edges()
    real(rk) :: x(3,4), v(3,4), x0(3,4), alpha, beta, n(3), g0, g1, w(4), w0(4), dl(3), moment(2), j
    real(rk), parameter :: m(4) = [0.7_rk, 1.1_rk, 1.3_rk, 0.9_rk], dt = 1.0e-3_rk
    logical :: crossed
    integer :: k, a
    x = reshape([-1.0_rk, 0.1_rk, -0.02_rk, 1.0_rk, -0.1_rk, -0.01_rk, 0.05_rk, -1.0_rk, 0.0_rk, -0.05_rk, 1.0_rk, 0.01_rk], [3, 4])
    v = reshape([30.0_rk, 5.0_rk, -20.0_rk, 25.0_rk, -5.0_rk, -22.0_rk, -3.0_rk, 8.0_rk, 1.0_rk, 2.0_rk, 6.0_rk, -1.0_rk], [3, 4])
    x0 = x - dt*v
    call edge_crossing(x(:,1), x(:,2), x(:,3), x(:,4), v(:,1), v(:,2), v(:,3), v(:,4), dt, alpha, beta, n, g0, g1, crossed)
    call edge_shares(x0(:,1), x0(:,2), x0(:,3), x0(:,4), n, alpha, beta, w0)
    w = [1.0_rk - alpha, alpha, -(1.0_rk - beta), -beta]
    j = 1.0_rk
    do k = 1, 2
      if (k == 2) w0 = w
      dl = 0.0_rk
      do a = 1, 4
        dl = dl + cross(x0(:,a), w0(a)*j*n)
      end do
      moment(k) = norm2(dl)/(j*maxval(abs(x)))
    end do
    call check('moving_edges_angular_momentum', crossed .and. moment(1) < 1.0e-14_rk .and. moment(2) > 1.0e-4_rk &
               .and. abs(sum(w0(1:2)) - 1.0_rk) < 1e-15_rk, 'moment about the start positions '//s(moment(1))// &
               ' of J |x| with edge_shares, '//s(moment(2))//' with the end''s closest points')
  end subroutine

  !> Passes of match_velocities over the slave nodes in the given order;
  !> v: the slave velocities (1..ns) then the master nodes' (ns+1..ns+3);
  !> dn: each slave node's accumulated normal change.
  !> solve_normal_lcp on problems solved by hand, and on the four-node
  !> strike (normal_rows_matrix from its rows): the same normal changes as
  !> the converged sweeps.
  subroutine test_normal_lcp()
    real(rk) :: m(ns,ns), b(ns), lam(ns), work(ns,ns+1), sep(2), v(3,ns+3), dn_sum(ns), w(0:3,ns), coef(0:3,ns), &
                nrm(3,ns), err
    integer :: node(0:3,ns), k
    logical :: free(ns), ok
    ! one row in contact, one not: lam = (0.5, 0), s = (0, 1.5)
    ! (within the solve's regularisation, 1e-10 of the largest diagonal)
    m(1:2,1:2) = reshape([2.0_rk, 1.0_rk, 1.0_rk, 2.0_rk], [2, 2])
    call solve_normal_lcp(2, ns, m, [-1.0_rk, 1.0_rk], lam(1:2), ok, work, free)
    call check('normal_lcp_one_row_by_hand', ok .and. maxval(abs(lam(1:2) - [0.5_rk, 0.0_rk])) < 1.0e-9_rk, &
               'lam '//s(lam(1))//' '//s(lam(2)))
    ! the first guess (row 2 alone) leaves row 1 approaching: one pivot,
    ! lam = (1/3, 5/3)
    m(1:2,1:2) = reshape([2.0_rk, -1.0_rk, -1.0_rk, 2.0_rk], [2, 2])
    call solve_normal_lcp(2, ns, m, [1.0_rk, -3.0_rk], lam(1:2), ok, work, free)
    call check('normal_lcp_pivot_by_hand', ok .and. maxval(abs(lam(1:2) - [1.0_rk/3, 5.0_rk/3])) < 1.0e-9_rk, &
               'lam '//s(lam(1))//' '//s(lam(2)))
    ! two rows on one gap (singular): any split with s = 0, none negative
    m(1:2,1:2) = 1.0_rk
    call solve_normal_lcp(2, ns, m, [-1.0_rk, -1.0_rk], lam(1:2), ok, work, free)
    sep = [-1.0_rk, -1.0_rk] + matmul(m(1:2,1:2), lam(1:2))
    call check('normal_lcp_one_gap_twice', ok .and. all(lam(1:2) >= 0.0_rk) .and. maxval(abs(sep)) < 1.0e-9_rk, &
               'separation rates '//s(sep(1))//' '//s(sep(2)))
    ! a positive definite problem on which flipping every infeasible row
    ! cycles (found by random search): without the safeguard the solve
    ! gives up after 19 guesses, with it single flips end the cycle,
    ! lam = (0, 0.36989, 0)
    m(1:3,1:3) = reshape([2.32720916_rk, 1.86466862_rk, -0.82147258_rk, 1.86466862_rk, 1.72237984_rk, -0.89653433_rk, &
                          -0.82147258_rk, -0.89653433_rk, 0.56902804_rk], [3, 3])
    b(1:3) = [-0.05157_rk, -0.63708579_rk, 0.58890262_rk]
    call solve_normal_lcp(3, ns, m, b(1:3), lam(1:3), ok, work, free, safeguarded=.false.)
    call check('normal_lcp_block_flips_cycle_without_the_safeguard', .not. ok, &
               'solved '//merge('yes', 'no ', ok)//' (the block flips must cycle here, or this case shows nothing)')
    call solve_normal_lcp(3, ns, m, b(1:3), lam(1:3), ok, work, free)   ! the default: safeguarded
    sep = 0
    if (ok) sep(1) = minval(b(1:3) + matmul(m(1:3,1:3), lam(1:3)))
    call check('normal_lcp_block_flips_cycle', ok .and. all(lam(1:3) >= 0.0_rk) .and. sep(1) > -1.0e-9_rk .and. &
               maxval(abs(lam(1:3) - [0.0_rk, 0.36988693_rk, 0.0_rk])) < 1.0e-7_rk, &
               'solved '//merge('yes', 'no ', ok)//', lam '//s(lam(1))//' '//s(lam(2))//' '//s(lam(3))// &
               ', smallest separation rate '//s(sep(1)))
    ! the four-node strike: rows 1-4, the triangle's nodes 5-7, unit masses
    call strike([1, 2, 3, 4], 400, 0.0_rk, v, dn_sum)
    call strike_rows(node, w, coef, nrm)
    do k = 1, ns
      b(k) = -dot_product(nrm(:,k), -[0.0_rk, 0.0_rk, -1.0_rk])     ! the slave nodes strike at 1 m/s, the master at rest
    end do
    call normal_rows_matrix(ns, ns, node, w, coef, nrm, m)
    call solve_normal_lcp(ns, ns, m, b, lam, ok, work, free)
    err = maxval(abs(lam - dn_sum))
    call check('normal_lcp_equals_converged_sweeps', ok .and. err < 1.0e-9_rk, &
               'largest difference from 400 sweeps '//s(err)//' m/s')
  end subroutine

  !> solve_friction_rows against the sweeps: the four-node strike with
  !> friction 0.3 (the answer of 400 sweeps), and two rows on one gap (a
  !> symmetric pair: rod node 1 on plate face (2,3,4), plate node 2 on rod
  !> face (1,5,6), sliding) where the sweeps converge slowly: the solve's
  !> answer is their fixed point (one more sweep changes nothing), Coulomb
  !> holds on both rows, and momentum is exact.
  subroutine test_friction_rows()
    real(rk) :: v(3,ns+3), dn_sum(ns), v_sw(3,ns+3), err
    real(rk) :: w(0:3,ns), coef(0:3,ns), nrm(3,ns), t_sum(3,ns), p_before(3), change, first_change
    real(rk) :: slip, worst_coulomb
    integer :: node(0:3,ns), k, it
    logical :: ok
    ! the four-node strike: rows 1-4 on the triangle of nodes 5-7, unit masses
    call strike([1, 2, 3, 4], 400, 0.3_rk, v_sw, dn_sum)
    call strike_rows(node, w, coef, nrm)
    do k = 1, ns
      v(:,k) = [0.2_rk*(k - 2), 0.1_rk, -1.0_rk]
    end do
    v(:,ns+1:) = 0.0_rk
    dn_sum = 0.0_rk
    t_sum = 0.0_rk
    call friction_solve(ns, node, w, coef, nrm, spread(0.3_rk, 1, ns), v, dn_sum, t_sum, ok)
    err = maxval(abs(v - v_sw))
    call check('friction_rows_equal_converged_sweeps', ok .and. err < 1.0e-9_rk, &
               'largest velocity difference from 400 sweeps '//s(err)//' m/s')
    ! two rows on one gap, both pushed and sliding
    npn(:,1) = [1, 2, 3, 4]
    npn(:,2) = [2, 1, 5, 6]
    np(:,1) = [0.0_rk, 0.0_rk, 1.0_rk]
    np(:,2) = [0.0_rk, 0.0_rk, -1.0_rk]
    mup = 0.3_rk
    call pair_start()
    ! the sweeps: 50 (the default iterations) leave them changing
    do it = 1, 50
      call pair_sweep(change)
      if (it == 1) first_change = change
    end do
    call check('friction_pair_sweeps_slow', change > 1.0e-6_rk*first_change, &
               'the 50th sweep still changes '//s(change)//' m/s (the first '//s(first_change)//')')
    call pair_start()
    p_before = matmul(vp, mp)
    call friction_solve(2, npn, wp, cp, np, mup, vp, dnp, tp, ok)
    call pair_sweep(change)
    worst_coulomb = 0.0_rk
    do k = 1, 2
      ! both pushed (dn > 0): matched normally, and sliding at the limit
      ! against the slip or sticking within it
      worst_coulomb = max(worst_coulomb, abs(dot_product(np(:,k), pair_rel(k))))
      slip = norm2(pair_rel(k) - dot_product(pair_rel(k), np(:,k))*np(:,k))
      if (slip > 1.0e-12_rk) then
        worst_coulomb = max(worst_coulomb, abs(norm2(tp(:,k)) - mup(k)*dnp(k)), &
          norm2(tp(:,k)/norm2(tp(:,k)) + (pair_rel(k) - dot_product(pair_rel(k), np(:,k))*np(:,k))/slip))
      else
        worst_coulomb = max(worst_coulomb, norm2(tp(:,k)) - mup(k)*dnp(k))
      end if
    end do
    ! sets of rows joined by shared nodes: rows 1 and 3 share node 7, row 4
    ! joins them through node 14 (row 3's), row 2 is alone
    block
      integer :: comp(4), n_comp, node_row(16)
      node_row = 0
      call row_components(4, reshape([1, 7, 8, 9, 2, 10, 11, 12, 3, 7, 13, 14, 4, 15, 16, 14], [4, 4]), node_row, comp, &
                          n_comp)
      call check('row_components_by_hand', n_comp == 2 .and. all(comp == [1, 2, 1, 1]) .and. all(node_row == 0), &
                 'sets '//trim(ints(comp))//', work array left clear: '//merge('yes', 'no ', all(node_row == 0)))
    end block
    call check('friction_pair_fixed_point', ok .and. change < 1.0e-12_rk .and. all(dnp > 0.0_rk) .and. &
               worst_coulomb < 1.0e-10_rk .and. maxval(abs(matmul(vp, mp) - p_before)) < 1.0e-14_rk, &
               'one sweep after it changes '//s(change)//' m/s; Coulomb off by '//s(worst_coulomb)// &
               '; momentum change '//s(maxval(abs(matmul(vp, mp) - p_before)))//' N s')
  end subroutine

  !> test_friction_rows' pair at the start of its pass
  subroutine pair_start()
    ! a case of a random search for slow sweeps (rod moving down at about
    ! 1 m/s, the plate's nodes slower, uneven masses and contact points)
    real(rk), parameter :: r(27) = [0.5594_rk, 0.4286_rk, 0.6159_rk, 0.4661_rk, 0.9717_rk, 0.2943_rk, 0.4366_rk, &
      0.6375_rk, 0.0378_rk, 0.1974_rk, 0.1562_rk, 0.3949_rk, 0.9005_rk, 0.3674_rk, 0.7639_rk, 0.2776_rk, 0.8830_rk, &
      0.7524_rk, 0.8196_rk, 0.6117_rk, 0.2382_rk, 0.7144_rk, 0.2859_rk, 0.9268_rk, 0.6117_rk, 0.0534_rk, 0.4918_rk]
    integer :: k
    vp(:,1) = [r(1) - 0.5_rk, r(2) - 0.5_rk, -1.0_rk]
    vp(:,5) = vp(:,1) + 0.3_rk*(r(3:5) - 0.5_rk)
    vp(:,6) = vp(:,1) + 0.3_rk*(r(6:8) - 0.5_rk)
    vp(:,3) = 0.3_rk*(r(9:11) - 0.5_rk)
    vp(:,4) = 0.3_rk*(r(12:14) - 0.5_rk)
    vp(:,2) = 0.3_rk*(r(15:17) - 0.5_rk)
    wp(:,1) = [-1.0_rk, 0.6_rk + 0.4_rk*r(18), 0.0_rk, 0.0_rk]
    wp(2,1) = (1.0_rk - wp(1,1))*r(19)
    wp(3,1) = 1.0_rk - wp(1,1) - wp(2,1)
    wp(:,2) = [-1.0_rk, 0.6_rk + 0.4_rk*r(20), 0.0_rk, 0.0_rk]
    wp(2,2) = (1.0_rk - wp(1,2))*r(21)
    wp(3,2) = 1.0_rk - wp(1,2) - wp(2,2)
    mp = 0.5_rk + r(22:27)
    do k = 1, 2
      cp(0,k) = 1.0_rk
      cp(1:3,k) = -wp(1:3,k)*mp(npn(0,k))/mp(npn(1:3,k))      ! shares = the contact point's weights
    end do
    dnp = 0.0_rk
    tp = 0.0_rk
  end subroutine
  !> one sweep of match_velocities over the pair; change: the largest velocity change
  subroutine pair_sweep(change)
    real(rk), intent(out) :: change
    real(rk) :: dvs(3), dvm(3,3), dn, dtv(3), v_old(3,nn)
    logical :: acted
    integer :: r, a
    v_old = vp
    do r = 1, 2
      call match_velocities(np(:,r), mp(npn(0,r)), vp(:,npn(0,r)), mp(npn(1:3,r)), vp(:,npn(1:3,r)), wp(1:3,r), &
                            wp(1:3,r), mup(r), dnp(r), tp(:,r), dvs, dvm, acted, dn, dtv)
      if (.not. acted) cycle
      dnp(r) = dnp(r) + dn
      tp(:,r) = tp(:,r) + dtv
      vp(:,npn(0,r)) = vp(:,npn(0,r)) + dvs
      do a = 1, 3
        vp(:,npn(a,r)) = vp(:,npn(a,r)) + dvm(:,a)
      end do
    end do
    change = maxval(abs(vp - v_old))
  end subroutine
  !> row k's slave velocity relative to its master point
  function pair_rel(k) result(u)
    integer, intent(in) :: k
    real(rk) :: u(3)
    u = vp(:,npn(0,k)) - matmul(vp(:,npn(1:3,k)), wp(1:3,k))
  end function

  !> The rows' normal and tangential changes solved together, as the
  !> contact driver's joint pass does (solve_friction_rows on
  !> normal_rows_matrix of each row's normal and tangent basis), applied to
  !> the velocities v (coef holds the masses).
  subroutine friction_solve(nr, node, w, coef, nrm, mu, v, dn_sum, t_sum, ok)
    integer, intent(in) :: nr, node(0:3,nr)
    real(rk), intent(in) :: w(0:3,nr), coef(0:3,nr), nrm(3,nr), mu(nr)
    real(rk), intent(inout) :: v(:,:), dn_sum(nr), t_sum(3,nr)
    logical, intent(out) :: ok
    integer :: e_node(0:3,3*nr), q, j, ie, p
    real(rk) :: e_w(0:3,3*nr), e_coef(0:3,3*nr), dir(3,3*nr), b(3*nr), x0(3*nr), x(3*nr), m(3*nr,3*nr), &
                jac(3*nr,3*nr+1), t1(3), t2(3)
    do q = 1, nr
      call tangent_basis(nrm(:,q), t1, t2)
      ie = 3*q - 2
      dir(:,ie) = nrm(:,q)
      dir(:,ie+1) = t1
      dir(:,ie+2) = t2
      x0(ie) = dn_sum(q)
      x0(ie+1) = dot_product(t1, t_sum(:,q))
      x0(ie+2) = dot_product(t2, t_sum(:,q))
      do j = 0, 2
        e_node(:,ie+j) = node(:,q)
        e_w(:,ie+j) = w(:,q)
        e_coef(:,ie+j) = coef(:,q)
        b(ie+j) = -dot_product(dir(:,ie+j), matmul(v(:,node(1:3,q)), w(1:3,q)) - v(:,node(0,q)))
      end do
    end do
    call normal_rows_matrix(3*nr, 3*nr, e_node, e_w, e_coef, dir, m)
    call solve_friction_rows(nr, 3*nr, m, b, x0, mu, x, ok, jac)
    if (.not. ok) return
    do ie = 1, 3*nr
      q = (ie + 2)/3
      do p = 0, 3
        v(:,node(p,q)) = v(:,node(p,q)) + (coef(p,q)*(x(ie) - x0(ie)))*dir(:,ie)
      end do
    end do
    do q = 1, nr
      dn_sum(q) = x(3*q-2)
      t_sum(:,q) = x(3*q-1)*dir(:,3*q-1) + x(3*q)*dir(:,3*q)
    end do
  end subroutine

  !> The four-node strike's rows as the joint solves take them: slave
  !> node k against the triangle's nodes ns+1..ns+3 (unit masses).
  subroutine strike_rows(node, w, coef, nrm)
    integer, intent(out) :: node(0:3,ns)
    real(rk), intent(out) :: w(0:3,ns), coef(0:3,ns), nrm(3,ns)
    real(rk) :: xs(3), n(3), dist, g(3), share(3)
    integer :: k
    do k = 1, ns
      xs = matmul(xm, gs(:,k)) + [0.0_rk, 0.0_rk, -1.0e-6_rk]
      call triangle_projection(xm, xs, n, dist, g)
      call master_shares(contact_weights_area, xm, xs, g, n, xm, xs, share)
      node(:,k) = [k, ns + 1, ns + 2, ns + 3]
      w(:,k) = [-1.0_rk, max(g, 0.0_rk)/sum(max(g, 0.0_rk))]
      coef(:,k) = [1.0_rk, -share]
      nrm(:,k) = n
    end do
  end subroutine

  subroutine strike(order, passes, friction, v, dn_sum)
    integer, intent(in) :: order(ns), passes
    real(rk), intent(in) :: friction
    real(rk), intent(out) :: v(3,ns+3), dn_sum(ns)
    real(rk) :: xs(3), n(3), dist, share(3,ns), m(ns+3), t_sum(3,ns), dvs(3), dvm(3,3), dn, dtv(3), gg(3,ns)
    logical :: acted
    integer :: it, j, k, a
    m = 1.0_rk
    do k = 1, ns
      xs = matmul(xm, gs(:,k)) + [0.0_rk, 0.0_rk, -1.0e-6_rk]      ! just behind the face
      call triangle_projection(xm, xs, n, dist, gg(:,k))
      call master_shares(contact_weights_area, xm, xs, gg(:,k), n, xm, xs, share(:,k))
      v(:,k) = [0.2_rk*(k - 2), 0.1_rk, -1.0_rk]
      if (friction <= 0.0_rk) v(1:2,k) = 0.0_rk
    end do
    v(:,ns+1:) = 0.0_rk
    dn_sum = 0.0_rk
    t_sum = 0.0_rk
    do it = 1, passes
      do j = 1, ns
        k = order(j)
        call match_velocities(n, m(k), v(:,k), m(ns+1:), v(:,ns+1:), gg(:,k), share(:,k), friction, dn_sum(k), &
                              t_sum(:,k), dvs, dvm, acted, dn, dtv)
        if (.not. acted) cycle
        dn_sum(k) = dn_sum(k) + dn
        t_sum(:,k) = t_sum(:,k) + dtv
        v(:,k) = v(:,k) + dvs
        do a = 1, 3
          v(:,ns+a) = v(:,ns+a) + dvm(:,a)
        end do
      end do
    end do
  end subroutine

  !> Each slave node matched (normal velocity equal to the master's at its
  !> contact point within 1e-9 m/s) or separating (faster away) with no
  !> accumulated normal change; gap: the largest violation.
  logical function admissible(v, dn_sum, gap)
    real(rk), intent(in) :: v(3,ns+3), dn_sum(ns)
    real(rk), intent(out) :: gap
    real(rk) :: rel
    integer :: k
    gap = 0.0_rk
    do k = 1, ns
      rel = v(3,k) - dot_product(gs(:,k), v(3,ns+1:))     ! > 0: separating
      if (dn_sum(k) > 1.0e-12_rk) then
        gap = max(gap, abs(rel))
      else
        gap = max(gap, max(-rel, 0.0_rk))
      end if
      if (dn_sum(k) < 0.0_rk) gap = huge(1.0_rk)
    end do
    admissible = gap < 1.0e-9_rk
  end function

  function s(x) result(str)
    real(rk), intent(in) :: x
    character(len=:), allocatable :: str
    character(len=16) :: b
    write(b, '(es10.3)') x
    str = trim(adjustl(b))
  end function
end program test_contact_kernels
