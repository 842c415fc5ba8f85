!> The contact pass of each cycle (after the nodes have moved, before the
!> halo exchange): each rank gets the state of the contact nodes near its
!> share of the slave nodes and searches for that share (penetration test,
!> triangle, shares); the nodes found go to every rank, which all match the
!> velocities (friction, iterations) over them in ascending global id and
!> return them to the surface; each keeps the results for its own nodes.
!> The search divides among the ranks, the matching over the nodes found
!> is repeated; bitwise the same on any number of ranks (design.md D9).
module udar_contact
  use udar_kinds, only: rk, i8, pi
  use udar_exact_sum, only: exact_limbs, exact_add
  use udar_domain, only: domain_t
  use udar_particle_model, only: particles_t
  use udar_contact_model, only: contact_t, interface_t, neighbour_across, contact_grow_nodes, joint_solve_rows, &
      joint_dense_rows, on_symmetry_plane
  use udar_contact_search, only: grid_build, grid_cell, ensure
  use udar_contact_kernels, only: corner_angle, match_velocities, return_on_planes, solve_friction_rows, row_components, edge_shares, solve_normal_lcp, normal_rows_matrix, contact_point, &
                                  edge_crossing, behind_not, behind_face, behind_seam
  use udar_contact_faces, only: face_projection, face_shares, closest_on_face, seam_contact, element_coordinates, &
                                face_behind_surface, face_beside_sharp_edge, points_inside_elements
  use udar_fracture, only: el_eroded
  use udar_ordering, only: find_sorted
  use udar_vectors, only: gather_columns, tangent_basis
  use udar_config, only: geometry_axisymmetric
  use udar_comms, only: comms_size, comms_rank, comms_allgather_count, comms_allgatherv_int, comms_allgatherv_real, &
                        comms_max, comms_alltoall_counts, comms_alltoallv_real, comms_wtime
  implicit none
  private
  public :: contact_distribute, contact_enforce, contact_overlaps, contact_settle, contact_pressure, contact_extent, &
            contact_keep_velocities, contact_work, contact_add_particles, contact_refresh_masses

  !> a projection this far outside a triangle (in area coordinates) still
  !> counts as on it: no slave node slips through the seam of two triangles
  real(rk), parameter :: edge_tolerance = 1.0e-3_rk
  !> a point this far inside a master element (in its area coordinates)
  !> is inside it, not on its boundary up to rounding
  real(rk), parameter :: overlap_tolerance = 1.0e-12_rk
  !> penetration beyond one step's approach still taken as crossed (of the
  !> mean master edge): rounding and the master triangle's own motion
  real(rk), parameter :: residual_tolerance = 1.0e-3_rk
  !> the velocity matching's passes have converged (tolerance = 0) once the
  !> largest change a pass makes is this share of the first pass's: to
  !> round-off, so that the answer does not depend on the order of the nodes
  real(rk), parameter :: contact_relative_tolerance = 1.0e-10_rk
  !> Sweeps of a joint pass with friction after which it is solved
  !> together (match_passes)
  integer, parameter :: friction_solve_after = 8
  !> a pass of fewer rows is matched by every rank (the sharing would cost more)
  integer, parameter :: spread_rows = 32
  !> Cycle passes without a change of the surfaces after which the
  !> candidate lists are built with the skin again (full_search).
  integer, parameter :: quiet_passes_for_skin = 4
  !> a return to the surface moves a slave node by at most this fraction of
  !> the smallest altitude of its elements: no element loses more than this
  !> share of its volume to a jump that no velocity (and no work) goes with;
  !> what is left is taken in the next cycles
  real(rk), parameter :: return_fraction = 0.02_rk
  ! the records the ranks exchange: a found slave node (slave index, triangle,
  ! kind, depth, normal, area coordinates, shares; the slave node's position,
  ! velocity and altitude, the triangle's nodes' positions and velocities),
  ! a node moved by its searcher (contact node, position) and a node's state
  ! (contact node, position, velocity, altitude)
  integer, parameter :: rec_found = 38, rec_moved = 4, rec_state = 8
  integer, parameter :: kind_found = 1, kind_separating = 2, kind_valley = 3
  !> a valley's two faces fold by more than about 37 degrees (the cosine of
  !> their normals' angle below this): at smaller folds one face's matching
  !> leaves little drift through the other, and the velocity matching's
  !> passes, which converge like the cosine squared for a node held by
  !> two rows, would take hundreds of sweeps (at 0.94: 115 of 171 passes on
  !> the rod deck stopped unconverged at 50)
  real(rk), parameter :: valley_cos = 0.8_rk
  !> the parts of a pass (detect): finding the slave nodes, and after the
  !> velocity matching (match_passes) the impulses and the returns
  integer, parameter :: stage_search = 1, stage_finish = 2, stage_both = 3, stage_returns = 4

contains

  !> Local view and gather layout of the contact nodes on this rank
  !> (collective).
  subroutine contact_distribute(ct, loc)
    type(contact_t), intent(inout) :: ct
    type(domain_t), intent(in) :: loc
    integer, allocatable :: pos_of_global(:), owned_counts(:)
    integer :: n, p, np
    if (ct%n_interfaces == 0) return
    np = comms_size()
    allocate(pos_of_global(loc%n_global_nodes), source=0)
    pos_of_global(ct%gidx) = [(p, p = 1, ct%n_nodes)]
    allocate(ct%local(ct%n_nodes), source=0)
    do n = 1, loc%n_nodes
      p = pos_of_global(loc%nd_gidx(n))
      if (p > 0) ct%local(p) = n
    end do
    ct%owned_pos = pack([(p, p = 1, ct%n_nodes)], ct%local > 0)
    ct%owned_pos = pack(ct%owned_pos, ct%local(ct%owned_pos) <= loc%n_owned_nodes)
    allocate(owned_counts(0:np-1), ct%counts(0:np-1), ct%gather_pos(ct%n_nodes))
    call comms_allgather_count(size(ct%owned_pos), owned_counts)
    call comms_allgatherv_int(ct%owned_pos, owned_counts, ct%gather_pos)
    ct%counts = 7*owned_counts
    allocate(ct%rec_counts(0:np-1), ct%rec_next(0:np-1), ct%rec_end(0:np-1), ct%x_counts(0:np-1), ct%x_rcounts(0:np-1), &
             ct%region_counts(0:np-1), ct%regions(6*np))
    ct%region_counts = 6
    ct%x_counts = 0
    allocate(ct%fresh(ct%n_nodes), source=0)
    ct%full_state = any([(ct%ifc(p)%edges, p = 1, ct%n_interfaces)])
    allocate(ct%send(7*size(ct%owned_pos) + 1), ct%recv(7*ct%n_nodes))
    allocate(ct%v_prev(3, size(ct%owned_pos)), ct%v_pre(3, size(ct%owned_pos)))
  end subroutine

  !> Slave nodes behind their master surface before the first cycle:
  !> counted, the deepest named, and moved onto the surface if the interface
  !> asks for it. Returns a report line per interface.
  subroutine contact_overlaps(ct, dom, lines)
    type(contact_t), intent(inout) :: ct
    type(domain_t), intent(inout) :: dom
    character(len=300), allocatable, intent(out) :: lines(:)
    integer :: i, n_found, worst
    real(rk) :: depth
    allocate(lines(ct%n_interfaces))
    if (ct%n_interfaces == 0) return
    call gather_state(ct, dom)
    do i = 1, ct%n_interfaces
      ! a node inside the master body, behind the surface by up to one
      ! master element (ahead of a sharp edge or corner a node can be behind
      ! the planes of faces beyond it without being inside)
      call detect(ct, ct%ifc(i), ct%ifc(i)%h_mean, ct%ifc(i)%move_overlaps, 0.0_rk, stage_both, n_found, depth, worst, &
                  only=ct%ifc(i)%start_inside)
      if (allocated(ct%ifc(i)%start_inside)) deallocate(ct%ifc(i)%start_inside)
      if (n_found == 0) then
        write(lines(i), '(a)') 'contact '//trim(ct%ifc(i)%name)//': no initial overlap'
      else
        write(lines(i), '(a,i0,a,es10.3,a,i0,a,3es11.3,a)') 'contact '//trim(ct%ifc(i)%name)//': ', n_found, &
          ' slave nodes start behind the master surface, deepest ', depth, ' m (node ', ct%gidx(worst), ' at ', &
          ct%x(:,worst), ' m)'//merge('; moved onto the surface', '                        ', ct%ifc(i)%move_overlaps)
      end if
    end do
    call scatter_state(ct, dom)
  end subroutine

  !> After the surfaces changed (erosion): slave nodes a hair (1 % of the
  !> mean master edge) behind a newly exposed face are put on it (a node
  !> flush against an element that is gone); deeper ones came through an
  !> element that is gone, and the next pass takes them with the velocities.
  subroutine contact_settle(ct, dom, pt)
    type(contact_t), intent(inout) :: ct
    type(domain_t), intent(inout) :: dom
    type(particles_t), intent(inout) :: pt
    integer :: i, n_found, worst
    real(rk) :: depth, vmax
    if (ct%n_interfaces == 0) return
    call gather_state(ct, dom)
    call particles_in(ct, pt, vmax)
    do i = 1, ct%n_interfaces
      call detect(ct, ct%ifc(i), 0.01_rk*ct%ifc(i)%h_mean, .true., 0.0_rk, stage_both, n_found, depth, worst)
      ! (a symmetric pair: its first direction's returns again, contact_enforce)
      if (i == 1) cycle
      if (ct%ifc(i-1)%partner == i) &
        call detect(ct, ct%ifc(i-1), 0.01_rk*ct%ifc(i-1)%h_mean, .true., 0.0_rk, stage_returns, n_found, depth, worst)
    end do
    call place_new_particles(ct, dom)
    call scatter_state(ct, dom)
    call particles_out(ct, pt)
  end subroutine

  !> Particles made since the last call (ct%particles_placed on) inside an
  !> element of a master body they are slave nodes of (the element they
  !> came from overlapped it: a master corner through a failing element)
  !> are put at the nearest point of the master surface (within
  !> placement_reach mean master edges; else left, and counted). Not
  !> placed, such a particle has crossed no face and the passes let it
  !> through. The pass's rules for telling a node behind a face (sharp
  !> edges, seams) are not needed: it is known to be inside. Each rank tests
  !> its owned elements; what they found goes to every rank, which all have
  !> every contact node's state here and place them alike (collective).
  subroutine place_new_particles(ct, dom)
    type(contact_t), intent(inout) :: ct
    type(domain_t), intent(in) :: dom
    real(rk), parameter :: placement_reach = 3.0_rk
    integer :: i, k, q, t, first, n_new, n_in, nf, best, p
    integer, allocatable :: elems(:), slot(:), found(:), counts(:), all_found(:)
    logical, allocatable :: inside(:), flag(:)
    real(rk) :: xa(3,3), c(3), g(3), d, best_d, best_c(3), reach
    first = ct%particles_placed + 1
    n_new = ct%n_nodes - ct%n_mesh - ct%particles_placed
    ct%particles_placed = ct%n_nodes - ct%n_mesh
    if (n_new <= 0) return
    allocate(counts(0:comms_size()-1))
    do i = 1, ct%n_interfaces
      associate (it => ct%ifc(i))
        if (it%self .or. .not. allocated(it%master_body)) cycle
        nf = size(it%tri, 1)
        reach = placement_reach*it%h_mean
        ! the new particles among its slave nodes (their slave index)
        allocate(slot(n_new))
        n_in = 0
        do q = first, first + n_new - 1
          k = find_sorted(it%slave, ct%n_mesh + q)
          if (k == 0) cycle
          n_in = n_in + 1
          slot(n_in) = k
        end do
        if (n_in > 0) then
          elems = pack(dom%el_owned_list, dom%el_state(dom%el_owned_list) /= el_eroded .and. &
                                          it%master_body(dom%el_part(dom%el_owned_list)))
          allocate(inside(n_in))
          call points_inside_elements(dom%el_conn, dom%nd_x, elems, ct%x(:, it%slave(slot(1:n_in))), inside)
          found = pack(slot(1:n_in), inside)
          call comms_allgather_count(size(found), counts)
          allocate(all_found(sum(counts)))
          call comms_allgatherv_int(found, counts, all_found)
          ! (a particle on the boundary of two ranks' elements is found twice)
          allocate(flag(size(it%slave)), source=.false.)
          flag(all_found) = .true.
          do k = 1, size(it%slave)
            if (.not. flag(k)) cycle
            p = it%slave(k)
            ct%particles_inside = ct%particles_inside + 1
            best = 0
            best_d = reach
            do t = 1, size(it%tri, 2)
              ! (no face lies in a symmetry plane, contact_setup: a particle
              ! made on the plane goes to the real surface)
              call gather_columns(xa, ct%x, it%tri(:,t))
              if (any(ct%x(:,p) < minval(xa(:,1:nf), dim=2) - best_d) .or. &
                  any(ct%x(:,p) > maxval(xa(:,1:nf), dim=2) + best_d)) cycle
              call closest_on_face(xa(:,1:nf), ct%x(:,p), c, g)
              d = norm2(c - ct%x(:,p))
              if (d >= best_d) cycle
              best = t; best_d = d; best_c = c
            end do
            if (best == 0) then
              ct%particles_left_inside = ct%particles_left_inside + 1
              cycle
            end if
            ct%particle_inside_deepest = max(ct%particle_inside_deepest, best_d)
            ct%x(:,p) = best_c
          end do
          deallocate(inside, all_found, flag)
        end if
        deallocate(slot)
      end associate
    end do
  end subroutine

  !> The particles made since the last call join the contact nodes
  !> (n_mesh + q is particle q), with their part, mass and size (their
  !> smoothing length bounds their returns as an element's altitude bounds
  !> a node's).
  subroutine contact_add_particles(ct, pt, placed)
    type(contact_t), intent(inout) :: ct
    type(particles_t), intent(in) :: pt
    !> they are where they belong (a restart's: put on the master surfaces
    !> in the run that made them), place_new_particles passes them by
    logical, intent(in), optional :: placed
    integer :: q, p, old
    integer, allocatable :: parts(:)
    if (ct%n_interfaces == 0) return
    old = ct%n_nodes - ct%n_mesh
    if (pt%n <= old) return
    call contact_grow_nodes(ct, ct%n_mesh + pt%n)
    allocate(parts(pt%n), source=0)
    if (old > 0) parts(1:old) = ct%particle_part(1:old)
    call move_alloc(parts, ct%particle_part)
    do q = old + 1, pt%n
      p = ct%n_mesh + q
      ct%x0(:,p) = pt%x(:,q)
      ct%x(:,p) = pt%x(:,q)
      ct%v(:,p) = pt%v(:,q)
      ct%m(p) = pt%m(q)
      ! (its smoothing length, fixed at conversion: a restart sets the same)
      ct%h(p) = pt%h(q)
      ct%particle_part(q) = pt%part(q)
    end do
    if (present(placed)) then
      if (placed) ct%particles_placed = pt%n
    end if
  end subroutine

  !> The masses of the mesh's contact nodes again from their owners, where
  !> they changed (nodes that lost elements to particles; collective).
  subroutine contact_refresh_masses(ct, dom)
    type(contact_t), intent(inout) :: ct
    type(domain_t), intent(in) :: dom
    integer :: k, p, n_send, r
    if (ct%n_interfaces == 0) return
    call ensure(ct%rec_send, 2*size(ct%owned_pos))
    n_send = 0
    do k = 1, size(ct%owned_pos)
      p = ct%owned_pos(k)
      if (ct%m(p) == dom%nd_mass(ct%local(p))) cycle
      ct%rec_send(n_send+1:n_send+2) = [real(p, rk), dom%nd_mass(ct%local(p))]
      n_send = n_send + 2
    end do
    call gather_records(ct, n_send)
    do r = 0, sum(ct%rec_counts) - 2, 2
      ct%m(nint(ct%rec_recv(r+1))) = ct%rec_recv(r+2)
    end do
  end subroutine

  !> The particles' state into the contact nodes n_mesh + q (every rank
  !> has them all: fresh on every rank); vmax raised to the fastest.
  subroutine particles_in(ct, pt, vmax)
    type(contact_t), intent(inout) :: ct
    type(particles_t), intent(in) :: pt
    real(rk), intent(inout) :: vmax
    integer :: q, p
    do q = 1, ct%n_nodes - ct%n_mesh
      p = ct%n_mesh + q
      ct%x(:,p) = pt%x(:,q)
      ct%v(:,p) = pt%v(:,q)
      ct%fresh(p) = ct%stamp
      vmax = max(vmax, norm2(pt%v(:,q)))
    end do
  end subroutine

  !> The particles' corrected state back.
  subroutine particles_out(ct, pt)
    type(contact_t), intent(in) :: ct
    type(particles_t), intent(inout) :: pt
    integer :: q, p
    do q = 1, ct%n_nodes - ct%n_mesh
      p = ct%n_mesh + q
      pt%x(:,q) = ct%x(:,p)
      pt%v(:,q) = ct%v(:,p)
    end do
  end subroutine

  !> One contact pass: each rank searches for its share of the slave
  !> nodes in its neighbourhood of the surfaces; every rank matches the
  !> velocities of all the nodes found, in one order.
  subroutine contact_enforce(ct, dom, dt, pt)
    type(contact_t), intent(inout) :: ct
    type(domain_t), intent(inout) :: dom
    real(rk), intent(in) :: dt
    type(particles_t), intent(inout) :: pt
    integer :: i, k, last, n_found, worst, stage
    real(rk) :: vmax, margin(2), depth
    real(rk) :: t0
    if (ct%n_interfaces == 0) return
    t0 = comms_wtime()
    ! nothing crosses unseen: a slave node and a triangle close by at most
    ! twice the fastest contact node's step
    if (ct%full_state .or. comms_size() == 1) then
      call gather_state(ct, dom)
      vmax = 0
      do i = 1, ct%n_mesh
        vmax = max(vmax, norm2(ct%v(:,i)))
      end do
      call particles_in(ct, pt, vmax)
    else
      ! (the particles first: the exchange's regions take in their share
      ! of them, and its reach their speed; fresh after it)
      vmax = 0
      call particles_in(ct, pt, vmax)
      call exchange_neighbourhood(ct, dom, dt, vmax)
      call particles_in(ct, pt, vmax)
    end if
    ct%seconds_exchange = ct%seconds_exchange + (comms_wtime() - t0)
    ct%impulse = 0
    ct%dt_last = dt
    ! each interface, or a symmetric contact's two directions together:
    ! find, match the velocities, then impulses and returns. The particles
    ! kept out of their own bodies go between the others' matching and
    ! their returns, so that no pass moves a mesh contact's faces once its
    ! nodes are out (a rod particle's push on the rod's face sent a rod
    ! node 5e-4 h into the plate, validation.md 4zn; the particles' passes
    ! first instead let the long rod's particles through the block)
    do stage = 1, 3
      i = 1
      do while (i <= ct%n_interfaces)
        last = i
        if (ct%ifc(i)%partner == i + 1) last = i + 1
        if (ct%ifc(i)%own_particles .neqv. stage == 2) then
          i = last + 1
          cycle
        end if
        if (stage <= 2) then
          do k = i, last
            margin(k-i+1) = 2.0_rk*vmax*dt + 0.05_rk*ct%ifc(k)%h_mean
            call detect(ct, ct%ifc(k), margin(k-i+1), .true., dt, stage_search, n_found, depth, worst)
          end do
          call match_passes(ct, i, last, dt)
        end if
        if (stage >= 2) then
          t0 = comms_wtime()
          do k = i, last
            margin(k-i+1) = 2.0_rk*vmax*dt + 0.05_rk*ct%ifc(k)%h_mean
            call detect(ct, ct%ifc(k), margin(k-i+1), .true., dt, stage_finish, n_found, depth, worst)
          end do
          ! a symmetric pair: the second direction's returns move the
          ! first's master faces, which can take its nodes, already out,
          ! back inside (a rod node at a plate vertex the plate's return
          ! moved, validation.md 4zo): the first's returns once more
          if (last > i) call detect(ct, ct%ifc(i), margin(1), .true., dt, stage_returns, n_found, depth, worst)
          ! edge against edge (a symmetric pair's edges once)
          if (ct%ifc(i)%edges) call edge_pass(ct, ct%ifc(i), dt, margin(1))
          ct%seconds_replicated = ct%seconds_replicated + (comms_wtime() - t0)
        end if
        i = last + 1
      end do
    end do
    call scatter_state(ct, dom)
    call particles_out(ct, pt)
  end subroutine

  !> Edge-to-edge contact (&contact edges): every slave feature edge that
  !> crossed a master feature edge during the step (edge_crossing) gets the
  !> impulse along their common normal, at their closest points, that stops
  !> their approach, and with friction the tangential one that stops their
  !> slip, at most friction times the normal one: the four nodes' velocities change
  !> in proportion to their linear weights (edge_shares: of the points
  !> whose join was along the normal at the start of the step) over their
  !> masses (momentum exact, and no moment about the start positions), their
  !> positions as if the corrected velocities had been used; what is still
  !> crossed goes back with the slave edge, in bounded steps as a node's
  !> return does.
  subroutine edge_pass(ct, it, dt, margin)
    type(contact_t), intent(inout) :: ct
    type(interface_t), intent(inout) :: it
    real(rk), intent(in) :: dt, margin
    real(rk) :: reach, mid(3), alpha, beta, n(3), g0, g1, w(4), w0(4), wm, u, j, room, dv(3), jt(3), slip(3)
    integer :: nm, e, f, s, c, nodes(4), a
    logical :: crossed
    it%n_edge_contacts = 0
    nm = size(it%edge_m, 2)
    if (nm == 0 .or. size(it%edge_s, 2) == 0 .or. dt <= 0.0_rk) return
    ! a crossing lies within half the slave edge of its midpoint
    reach = 0
    do e = 1, size(it%edge_s, 2)
      reach = max(reach, 0.5_rk*norm2(ct%x(:,it%edge_s(2,e)) - ct%x(:,it%edge_s(1,e))))
    end do
    reach = reach + margin
    do f = 1, nm
      associate (xa => ct%x(:,it%edge_m(1,f)), xb => ct%x(:,it%edge_m(2,f)), &
                 va => ct%v(:,it%edge_m(1,f)), vb => ct%v(:,it%edge_m(2,f)))
        it%edge_lo(:,f) = min(xa, xb, xa - dt*va, xb - dt*vb) - reach
        it%edge_hi(:,f) = max(xa, xb, xa - dt*va, xb - dt*vb) + reach
      end associate
    end do
    call grid_build(it%edge_grid, it%edge_lo(:,1:nm), it%edge_hi(:,1:nm))
    do e = 1, size(it%edge_s, 2)
      mid = 0.5_rk*(ct%x(:,it%edge_s(1,e)) + ct%x(:,it%edge_s(2,e)))
      c = grid_cell(it%edge_grid, mid)
      if (c == 0) cycle
      do s = it%edge_grid%start(c), it%edge_grid%start(c+1) - 1
        f = it%edge_grid%items(s)
        if (any(mid < it%edge_lo(:,f)) .or. any(mid > it%edge_hi(:,f))) cycle
        nodes = [it%edge_s(:,e), it%edge_m(:,f)]
        if (any(nodes(1:2) == nodes(3)) .or. any(nodes(1:2) == nodes(4))) cycle
        call edge_crossing(ct%x(:,nodes(1)), ct%x(:,nodes(2)), ct%x(:,nodes(3)), ct%x(:,nodes(4)), &
                           ct%v(:,nodes(1)), ct%v(:,nodes(2)), ct%v(:,nodes(3)), ct%v(:,nodes(4)), dt, &
                           alpha, beta, n, g0, g1, crossed)
        if (.not. crossed) cycle
        it%n_edge_contacts = it%n_edge_contacts + 1
        it%edge_max_depth = max(it%edge_max_depth, -g1)
        ! signed weights: the slave edge's closest point moves along +n, the
        ! master's along -n; the approach u measured at the end's closest
        ! points, the impulse shared by the start's (edge_shares)
        w = [1.0_rk - alpha, alpha, -(1.0_rk - beta), -beta]
        u = dot_product(n, w(1)*ct%v(:,nodes(1)) + w(2)*ct%v(:,nodes(2)) + w(3)*ct%v(:,nodes(3)) &
                           + w(4)*ct%v(:,nodes(4)))
        if (u < 0.0_rk) then
          call edge_shares(ct%x(:,nodes(1)) - dt*ct%v(:,nodes(1)), ct%x(:,nodes(2)) - dt*ct%v(:,nodes(2)), &
                           ct%x(:,nodes(3)) - dt*ct%v(:,nodes(3)), ct%x(:,nodes(4)) - dt*ct%v(:,nodes(4)), &
                           n, alpha, beta, w0)
          wm = sum(w*w0/ct%m(nodes))
          j = -u/wm
          call push(j, n)
          it%normal_impulse = it%normal_impulse + j
          it%master_impulse = it%master_impulse - j*n      ! the master side's weights sum to -1
          g1 = g1 - dt*u
          ! friction: the tangential impulse that stops the closest points'
          ! slip (the same weights, so the same effective mass), at most
          ! friction times the normal one (Coulomb)
          if (it%friction > 0.0_rk) then
            slip = w(1)*ct%v(:,nodes(1)) + w(2)*ct%v(:,nodes(2)) + w(3)*ct%v(:,nodes(3)) + w(4)*ct%v(:,nodes(4))
            jt = -(slip - dot_product(slip, n)*n)/wm
            if (norm2(jt) > it%friction*j) jt = (it%friction*j/norm2(jt))*jt
            call push(1.0_rk, jt)
            it%friction_impulse = it%friction_impulse + norm2(jt)
            it%master_impulse = it%master_impulse - jt
          end if
        end if
        if (g1 < 0.0_rk) then
          room = return_room(min(ct%h(nodes(1)), ct%h(nodes(2))))
          ct%x(:,nodes(1)) = ct%x(:,nodes(1)) + min(-g1, room)*n
          ct%x(:,nodes(2)) = ct%x(:,nodes(2)) + min(-g1, room)*n
        end if
      end do
    end do
    it%edge_contacts_total = it%edge_contacts_total + it%n_edge_contacts
  contains
    !> The impulse c*jv on the pair's closest points, shared by the start's
    !> weights w0 over the four nodes' masses: their velocities change, and
    !> their positions by the change over the step.
    subroutine push(c, jv)
      real(rk), intent(in) :: c, jv(3)
      do a = 1, 4
        dv = (w0(a)*c/ct%m(nodes(a)))*jv
        ct%v(:,nodes(a)) = ct%v(:,nodes(a)) + dv
        ct%x(:,nodes(a)) = ct%x(:,nodes(a)) + dt*dv
      end do
    end subroutine
  end subroutine

  !> The found slave nodes of every rank's search (records of rec_found
  !> reals in ct%rec_send(1:n_rec)) on every rank, in ascending slave
  !> index: their nodes' states current everywhere (the separating ones
  !> where their searcher put them back), the others the pass's active
  !> list; the deep ones counted (collective).
  subroutine share_found(ct, it, n_rec, depth_limit, dt, n_found, deepest, worst)
    type(contact_t), intent(inout) :: ct
    type(interface_t), intent(inout) :: it
    integer, intent(in) :: n_rec
    real(rk), intent(in) :: depth_limit, dt
    integer, intent(out) :: n_found, worst
    real(rk), intent(out) :: deepest
    integer :: q, r, k, kq, ps, best_q, np, t(3), a, nf
    real(rk) :: dist
    np = comms_size()
    nf = size(it%tri, 1)
    call gather_records(ct, n_rec)
    ! the states of the nodes found and of their triangles' nodes, current
    ! on every rank: the triangles' first, then the slave nodes' (a slave
    ! node of a self-contact put back is another's triangle node)
    do r = 0, sum(ct%rec_counts) - rec_found, rec_found
      t(1:nf) = it%tri(:, nint(ct%rec_recv(r+2)))
      do a = 1, nf
        ct%x(:,t(a)) = ct%rec_recv(r+18+3*a:r+20+3*a)
        ct%v(:,t(a)) = ct%rec_recv(r+27+3*a:r+29+3*a)
        ct%fresh(t(a)) = ct%stamp
      end do
    end do
    do r = 0, sum(ct%rec_counts) - rec_found, rec_found
      ps = it%slave(nint(ct%rec_recv(r+1)))
      ct%x(:,ps) = ct%rec_recv(r+14:r+16)
      ct%v(:,ps) = ct%rec_recv(r+17:r+19)
      ct%h(ps) = ct%rec_recv(r+20)
      ct%fresh(ps) = ct%stamp
    end do
    ! merge the ranks' ascending runs: rank q's next record at rec_next(q),
    ! its run ending at rec_end(q)
    ct%rec_next(0) = 0
    do q = 1, np - 1
      ct%rec_next(q) = ct%rec_next(q-1) + ct%rec_counts(q-1)
    end do
    ct%rec_end(0:np-1) = ct%rec_next(0:np-1) + ct%rec_counts(0:np-1)
    n_found = 0
    deepest = 0
    worst = 0
    ! self-contact: in contact in this pass (found, not separating)
    if (it%self) it%touched = .false.
    do
      best_q = -1
      k = huge(1)
      do q = 0, np - 1
        if (ct%rec_next(q) >= ct%rec_end(q)) cycle
        kq = nint(ct%rec_recv(ct%rec_next(q) + 1))
        if (kq < k) then
          k = kq
          best_q = q
        end if
      end do
      if (best_q < 0) exit
      r = ct%rec_next(best_q)
      ct%rec_next(best_q) = r + rec_found
      associate (rec => ct%rec_recv(r+1:r+rec_found))
        ps = it%slave(k)
        dist = rec(4)
        if (-dist > depth_limit .and. dt > 0.0_rk .and. nint(rec(3)) /= kind_valley) then
          it%n_deep = it%n_deep + 1
          it%deep_max = max(it%deep_max, -dist)
        end if
        if (nint(rec(3)) == kind_separating) cycle
        if (nint(rec(3)) == kind_valley .and. dt > 0.0_rk) it%valley_total = it%valley_total + 1
        n_found = n_found + 1
        if (it%self) it%touched(k) = .true.
        if (-dist > deepest) then
          deepest = -dist
          worst = ps
        end if
        it%active(n_found) = ps
        it%slot(n_found) = k
        it%on_tri(n_found) = nint(rec(2))
        it%normal(:,n_found) = rec(5:7)
        it%area(:,n_found) = rec(8:10)
        it%share(:,n_found) = rec(11:13)
      end associate
    end do
  end subroutine

  !> The nodes every rank's owner moved (records of rec_moved reals in
  !> ct%rec_send(1:n_rec): contact node, position) put there on every rank
  !> (collective).
  subroutine share_positions(ct, n_rec)
    type(contact_t), intent(inout) :: ct
    integer, intent(in) :: n_rec
    integer :: r
    call gather_records(ct, n_rec)
    do r = 0, sum(ct%rec_counts) - rec_moved, rec_moved
      ct%x(:,nint(ct%rec_recv(r+1))) = ct%rec_recv(r+2:r+4)
    end do
  end subroutine

  !> ct%rec_send(1:n_rec) of every rank, concatenated in rank order, into
  !> ct%rec_recv; ct%rec_counts: how many reals came from each (collective).
  subroutine gather_records(ct, n_rec)
    type(contact_t), intent(inout) :: ct
    integer, intent(in) :: n_rec
    if (comms_size() == 1) then
      ct%rec_counts(0) = n_rec
      call ensure(ct%rec_recv, n_rec)
      ct%rec_recv(1:n_rec) = ct%rec_send(1:n_rec)
      return
    end if
    call comms_allgather_count(n_rec, ct%rec_counts)
    call ensure(ct%rec_recv, sum(ct%rec_counts))
    call comms_allgatherv_real(ct%rec_send(1:n_rec), ct%rec_counts, ct%rec_recv)
  end subroutine

  !> Point x mirrored in the line or plane m (unit normal m(1:3), offset m(4)).
  pure function mirrored(x, m) result(y)
    real(rk), intent(in) :: x(3), m(4)
    real(rk) :: y(3)
    y = x - (2.0_rk*(dot_product(m(1:3), x) - m(4)))*m(1:3)
  end function

  !> The move u of a node back onto a surface, shortened to room.
  pure function returned(u, room) result(d)
    real(rk), intent(in) :: u(3), room
    real(rk) :: d(3)
    real(rk) :: length
    length = norm2(u)
    d = u
    if (length > room) d = (room/length)*u
  end function

  !> How far a node whose elements' smallest altitude is h may be returned
  !> to the surface in one pass (unbounded before the first cycle, h huge:
  !> initial overlaps).
  pure real(rk) function return_room(h)
    real(rk), intent(in) :: h
    return_room = huge(1.0_rk)
    if (h < huge(1.0_rk)) return_room = return_fraction*h
  end function

  !> Velocity matching with friction of the slave nodes interfaces first..last
  !> found (projected Gauss-Seidel), set by set: the rows joined by shared
  !> nodes (pass_sets) do not act on each other, so each set is matched on
  !> its own, its sweeps repeated until one changes nothing (to round-off)
  !> or `iterations` (a correction moves master nodes that earlier slave
  !> nodes of the set were matched to). A set's answer then depends on its
  !> rows alone, not on how many others the pass has or on whether they have
  !> converged. Every velocity change dv also moves its node by dt dv, as
  !> if the corrected velocity had been used for the step. The pass's
  !> sweeps are its slowest set's; it is unconverged if any set is.
  subroutine match_passes(ct, first, last, dt)
    type(contact_t), intent(inout) :: ct
    integer, intent(in) :: first, last
    real(rk), intent(in) :: dt
    integer :: c, n_sets, i, np, me
    logical :: joint_pass, spread
    real(rk) :: t0
    if (dt <= 0.0_rk) return
    t0 = comms_wtime()
    call pass_sets(ct, first, last, n_sets)
    ! both directions of a gap in one pass (and self-contact): rows that
    ! constrain one gap from both sides converge slowly in sweeps
    ! (validation.md 4t), so their sets are solved together first
    joint_pass = last > first .or. ct%ifc(first)%self
    ! every rank has every row's state (share_found): on several ranks each
    ! matches its run of the sets and the answers are shared; which rank
    ! matches a set does not change its answer (rank-count independence)
    np = comms_size()
    me = comms_rank()
    spread = .false.
    if (np > 1 .and. n_sets > 0) spread = ct%set_start(n_sets+1) - 1 >= spread_rows
    do c = 1, n_sets
      if (spread) then
        if (set_rank(ct, c, n_sets, np) /= me) cycle
      end if
      call match_set(ct, first, last, ct%set_start(c), ct%set_start(c+1) - 1, joint_pass, dt, ct%set_sweeps(c), &
                     ct%set_converged(c))
    end do
    ct%seconds_matching = ct%seconds_matching + (comms_wtime() - t0)
    if (spread) then
      t0 = comms_wtime()
      call share_sets(ct, n_sets, np, me)
      ct%seconds_exchange = ct%seconds_exchange + (comms_wtime() - t0)
    end if
    do i = first, last
      if (n_sets == 0) cycle
      ct%ifc(i)%sweeps = ct%ifc(i)%sweeps + maxval(ct%set_sweeps(1:n_sets))
      if (.not. all(ct%set_converged(1:n_sets))) ct%ifc(i)%sweep_limit_hits = ct%ifc(i)%sweep_limit_hits + 1
    end do
  end subroutine

  !> The rank that matches set c of n_sets on np ranks: the sets in runs of
  !> about equal numbers of rows, by their first rows (so ascending in c).
  integer function set_rank(ct, c, n_sets, np)
    type(contact_t), intent(in) :: ct
    integer, intent(in) :: c, n_sets, np
    set_rank = int((int(ct%set_start(c) - 1, i8)*np)/(ct%set_start(n_sets+1) - 1))
  end function

  !> Every set's answer from the rank that matched it to every rank
  !> (collective): its sweeps and whether it converged, then for each row
  !> its accumulated impulses and the velocities and positions of its
  !> nodes, which are the set's alone (the sets share no node). The ranks'
  !> runs of sets are in set order, so the gathered records are too.
  subroutine share_sets(ct, n_sets, np, me)
    type(contact_t), intent(inout) :: ct
    integer, intent(in) :: n_sets, np, me
    integer, parameter :: rec_set = 2, rec_row = 4 + 6*4
    integer :: c, r, p, e, j, n_send, a, b
    ! (rank r's count in set_counts(r+1))
    call ensure(ct%set_counts, np)
    ct%set_counts(1:np) = 0
    do c = 1, n_sets
      r = set_rank(ct, c, n_sets, np)
      ct%set_counts(r+1) = ct%set_counts(r+1) + rec_set + rec_row*(ct%set_start(c+1) - ct%set_start(c))
    end do
    call ensure(ct%set_send, ct%set_counts(me+1))
    call ensure(ct%set_recv, sum(ct%set_counts(1:np)))
    n_send = 0
    do c = 1, n_sets
      if (set_rank(ct, c, n_sets, np) /= me) cycle
      ct%set_send(n_send+1:n_send+rec_set) = [real(ct%set_sweeps(c), rk), merge(1.0_rk, 0.0_rk, ct%set_converged(c))]
      n_send = n_send + rec_set
      do p = ct%set_start(c), ct%set_start(c+1) - 1
        associate (it => ct%ifc(ct%row_ifc(p)), k => ct%row_k(p))
          ct%set_send(n_send+1:n_send+4) = [it%dn_sum(k), it%t_sum(:,k)]
        end associate
        n_send = n_send + 4
        do e = 0, 3
          ct%set_send(n_send+1:n_send+6) = [ct%v(:,ct%row_node(e,p)), ct%x(:,ct%row_node(e,p))]
          n_send = n_send + 6
        end do
      end do
    end do
    call comms_allgatherv_real(ct%set_send(1:n_send), ct%set_counts(1:np), ct%set_recv)
    j = 0
    do c = 1, n_sets
      ct%set_sweeps(c) = nint(ct%set_recv(j+1))
      ct%set_converged(c) = ct%set_recv(j+2) > 0.5_rk
      j = j + rec_set
      a = ct%set_start(c)
      b = ct%set_start(c+1) - 1
      do p = a, b
        associate (it => ct%ifc(ct%row_ifc(p)), k => ct%row_k(p))
          it%dn_sum(k) = ct%set_recv(j+1)
          it%t_sum(:,k) = ct%set_recv(j+2:j+4)
        end associate
        j = j + 4
        do e = 0, 3
          ct%v(:,ct%row_node(e,p)) = ct%set_recv(j+1:j+3)
          ct%x(:,ct%row_node(e,p)) = ct%set_recv(j+4:j+6)
          j = j + 6
        end do
      end do
    end do
  end subroutine

  !> The rows of the pass of interfaces first..last (row r: slave node
  !> active(k) of interface i against its triangle), grouped in the sets
  !> joined by shared nodes (row_components): set c of n_sets is rows
  !> ct%set_start(c) to ct%set_start(c+1) - 1, the sets in the order of
  !> their first rows and each set's rows in the pass's order (interface,
  !> then k). Each row's nodes, weights, coefficients and normal as
  !> row_data gives them.
  subroutine pass_sets(ct, first, last, n_sets)
    type(contact_t), intent(inout) :: ct
    integer, intent(in) :: first, last
    integer, intent(out) :: n_sets
    integer :: n, i, k, r, p, nf, c
    n = 0
    do i = first, last
      n = n + ct%ifc(i)%n_pass
    end do
    call ensure_rows(ct, n)
    n_sets = 0
    if (n == 0) return
    r = 0
    do i = first, last
      nf = size(ct%ifc(i)%tri, 1)
      do k = 1, ct%ifc(i)%n_pass
        r = r + 1
        ct%found_ifc(r) = i
        ct%found_k(r) = k
        ct%found_node(0,r) = ct%ifc(i)%active(k)
        ct%found_node(1:nf,r) = ct%ifc(i)%tri(:,ct%ifc(i)%on_tri(k))
        ct%found_node(nf+1:3,r) = ct%found_node(nf,r)
      end do
    end do
    call row_components(n, ct%found_node(:,1:n), ct%node_row, ct%found_set(1:n), n_sets)
    call ensure_sets(ct, n_sets)
    ct%set_start(1:n_sets+1) = 0
    do r = 1, n
      c = ct%found_set(r)
      ct%set_start(c+1) = ct%set_start(c+1) + 1
    end do
    ct%set_start(1) = 1
    do c = 1, n_sets
      ct%set_start(c+1) = ct%set_start(c+1) + ct%set_start(c)
    end do
    ! (set_start(c) runs on as set c's next free row, then back)
    do r = 1, n
      c = ct%found_set(r)
      p = ct%set_start(c)
      ct%set_start(c) = p + 1
      ct%row_ifc(p) = ct%found_ifc(r)
      ct%row_k(p) = ct%found_k(r)
      call row_data(ct, ct%row_ifc(p), ct%row_k(p), ct%row_node(:,p), ct%row_w(:,p), ct%row_coef(:,p), &
                    ct%row_nrm(:,p))
    end do
    do c = n_sets, 2, -1
      ct%set_start(c) = ct%set_start(c-1)
    end do
    ct%set_start(1) = 1
  end subroutine

  !> Room in ct's row arrays for n rows.
  subroutine ensure_rows(ct, n)
    type(contact_t), intent(inout) :: ct
    integer, intent(in) :: n
    integer :: cap
    if (allocated(ct%row_ifc)) then
      if (size(ct%row_ifc) >= n) return
      deallocate(ct%row_node, ct%row_ifc, ct%row_k, ct%row_w, ct%row_coef, ct%row_nrm, ct%found_node, ct%found_ifc, &
                 ct%found_k, ct%found_set)
    end if
    cap = max(2*n, 64)
    allocate(ct%row_node(0:3,cap), ct%row_ifc(cap), ct%row_k(cap), ct%row_w(0:3,cap), ct%row_coef(0:3,cap), &
             ct%row_nrm(3,cap), ct%found_node(0:3,cap), ct%found_ifc(cap), ct%found_k(cap), ct%found_set(cap))
  end subroutine

  !> Room in ct's set arrays for n sets.
  subroutine ensure_sets(ct, n)
    type(contact_t), intent(inout) :: ct
    integer, intent(in) :: n
    if (allocated(ct%set_start)) then
      if (size(ct%set_start) >= n + 1) return
      deallocate(ct%set_start, ct%set_sweeps, ct%set_converged)
    end if
    allocate(ct%set_start(max(2*n, 64) + 1), ct%set_sweeps(max(2*n, 64)), ct%set_converged(max(2*n, 64)))
  end subroutine

  !> Row k of interface i: slave node node(0) against its triangle's
  !> nodes node(1:3) at weights w(1:3) (contact_point, as match_velocities
  !> takes them; w(0) = -1) with shares R (a change lam of the slave's
  !> velocity changes node p's by coef(p) lam: 1 for the slave, -R_a
  !> m_s/m_a for master node a, momentum exact), along unit normal nrm; a
  !> 2D segment's third slot is its second node again, of weight and share 0.
  subroutine row_data(ct, i, k, node, w, coef, nrm)
    type(contact_t), intent(in) :: ct
    integer, intent(in) :: i, k
    integer, intent(out) :: node(0:3)
    real(rk), intent(out) :: w(0:3), coef(0:3), nrm(3)
    integer :: a, nf
    associate (it => ct%ifc(i))
      nf = size(it%tri, 1)
      node(0) = it%active(k)
      node(1:nf) = it%tri(:,it%on_tri(k))
      node(nf+1:3) = node(nf)
      w(0) = -1.0_rk
      w(1:3) = contact_point(it%area(:,k))
      coef(0) = 1.0_rk
      do a = 1, 3
        coef(a) = -it%share(a,k)*ct%m(node(0))/ct%m(node(a))
      end do
      nrm = it%normal(:,k)
    end associate
  end subroutine

  !> The matching of the pass's rows a..b, one set (match_passes). In a
  !> joint pass the set's normal rows are solved together first
  !> (solve_set_normals); as those rows then trade impulse without
  !> changing a velocity, its sweeps stop on the nodes' net velocity change
  !> (theory.md 11). With friction a joint set alternates: sweeps of
  !> friction alone with the normals held at the joint solve's, then the
  !> normals solved again for the velocities friction left, to a fixed
  !> point. (Sweeps of both let two rows on one gap trade their normal
  !> changes along the solve's null space while their friction limits grow
  !> with them, validation.md 4zl.) Where that is slow (two rows on one gap
  !> have nearly the same friction too), every friction_solve_after sweeps
  !> the set is solved together, normals and friction
  !> (solve_set_friction), from where the alternation got, and ordinary
  !> sweeps take what rounding left. A set with a node on a symmetry plane
  !> then has its normals matched again as the planes let the nodes move
  !> (match_on_planes). sweeps: how many it took; converged: before
  !> `iterations`.
  subroutine match_set(ct, first, last, a, b, joint_pass, dt, sweeps, converged)
    type(contact_t), intent(inout) :: ct
    integer, intent(in) :: first, last, a, b
    logical, intent(in) :: joint_pass
    real(rk), intent(in) :: dt
    integer, intent(out) :: sweeps
    logical, intent(out) :: converged
    real(rk) :: first_change, resolve_change
    integer :: iter, iterations
    logical :: joint, held, solved, frictionless
    real(rk) :: tolerance
    first_change = 0
    iterations = ct%ifc(first)%iterations
    tolerance = ct%ifc(first)%tolerance
    frictionless = all(ct%ifc(first:last)%friction == 0.0_rk)
    joint = .false.
    if (joint_pass) call solve_set_normals(ct, a, b, frictionless, .false., dt, first_change, joint)
    held = joint .and. .not. frictionless
    converged = .false.
    sweeps = 0
    do iter = 1, iterations
      sweeps = iter
      if (joint) call keep_row_velocities(ct, a, b)
      if (held .and. mod(iter, friction_solve_after) == 1 .and. iter > 1) then
        call solve_set_friction(ct, a, b, dt, resolve_change, solved)
        held = .not. solved
      end if
      ! unsolved: the sweeps take the normals over from the last solve
      if (held .and. iter > 1) call solve_set_normals(ct, a, b, frictionless, .false., dt, resolve_change, held)
      call sweep_set(ct, a, b, joint, held, .false., dt, iter, tolerance, first_change, converged)
      if (converged) exit
    end do
    if (any_on_plane(ct, a, b)) call match_on_planes(ct, first, a, b, joint_pass, dt, first_change, sweeps, converged)
  end subroutine

  !> A set with nodes on symmetry planes, after match_set's matching,
  !> which moved them along the rows' own directions: each such node keeps
  !> the part of its change the planes allow (plane_direction; the
  !> velocity conditions would take the rest after the pass, leaving a row
  !> whose face leans out of the plane approaching by n_y^2 of its
  !> correction), then the set's normals are matched again, frictionless,
  !> with every node moving as its planes allow (match_velocities with the
  !> nodes' projections;
  !> in a joint pass solved together first), to convergence relative to
  !> the set's first change (set_change: this stage refines the set's
  !> answer). The friction stays as the matching left it, projected.
  !> sweeps and converged take in this stage's.
  subroutine match_on_planes(ct, first, a, b, joint_pass, dt, set_change, sweeps, converged)
    type(contact_t), intent(inout) :: ct
    integer, intent(in) :: first, a, b
    logical, intent(in) :: joint_pass
    real(rk), intent(in) :: dt, set_change
    integer, intent(inout) :: sweeps
    logical, intent(inout) :: converged
    real(rk) :: first_change, solve_change, tolerance
    integer :: iter, q, e, node
    logical :: joint, done
    real(rk) :: pv(3)
    do q = a, b
      do e = 0, 3
        node = ct%row_node(e,q)
        if (ct%plane_set(node) == 0) cycle
        pv = plane_direction(ct, node, ct%v(:,node))
        ct%x(:,node) = ct%x(:,node) - dt*(ct%v(:,node) - pv)
        ct%v(:,node) = pv
      end do
    end do
    tolerance = ct%ifc(first)%tolerance
    joint = .false.
    solve_change = 0
    if (joint_pass) call solve_set_normals(ct, a, b, .true., .true., dt, solve_change, joint)
    first_change = max(solve_change, set_change)
    done = .false.
    do iter = 1, ct%ifc(first)%iterations
      if (joint) call keep_row_velocities(ct, a, b)
      call sweep_set(ct, a, b, joint, .false., .true., dt, iter, tolerance, first_change, done)
      if (done) exit
    end do
    sweeps = sweeps + min(iter, ct%ifc(first)%iterations)
    converged = converged .and. done
  end subroutine

  !> Sweep iter of a set's matching (sweep_rows; held, on_planes as there)
  !> and its convergence test: the change it still made (in a joint set
  !> the nodes' net velocity change since keep_row_velocities), the set's
  !> scale first_change raised to its first sweep's, settled against it.
  subroutine sweep_set(ct, a, b, joint, held, on_planes, dt, iter, tolerance, first_change, converged)
    type(contact_t), intent(inout) :: ct
    integer, intent(in) :: a, b, iter
    logical, intent(in) :: joint, held, on_planes
    real(rk), intent(in) :: dt, tolerance
    real(rk), intent(inout) :: first_change
    logical, intent(out) :: converged
    real(rk) :: mismatch
    call sweep_rows(ct, a, b, held, on_planes, dt, mismatch)
    if (joint) mismatch = row_velocity_change(ct, a, b)
    ! the scale of the set: its first sweep, or the joint solve before it
    if (iter == 1) first_change = max(first_change, mismatch)
    ! converged: every node matched or released, its changes admissible
    converged = settled(mismatch, first_change, tolerance)
  end subroutine

  !> One sweep of the matching over rows a..b (match_velocities; held: the
  !> normals held at a joint solve's); on_planes: the normals alone, a row
  !> with a node on a symmetry plane matched as the planes let its nodes
  !> move (match_velocities with their projections). mismatch: the largest change the sweep
  !> still made, pushes and take-backs alike.
  subroutine sweep_rows(ct, a, b, held, on_planes, dt, mismatch)
    type(contact_t), intent(inout) :: ct
    integer, intent(in) :: a, b
    logical, intent(in) :: held, on_planes
    real(rk), intent(in) :: dt
    real(rk), intent(out) :: mismatch
    real(rk) :: dvs(3), dvm(3,3), dn, dtan(3), vm(3,3), mm(3), proj(3,3,0:3)
    integer :: p, k, ps, t, c, pa, nf
    logical :: closing
    mismatch = 0
    do p = a, b
      associate (it => ct%ifc(ct%row_ifc(p)))
        ! a face's nodes: 3 (a triangle) or 2 (a 2D segment, its third
        ! slot of weight and share 0 padded with a unit mass at rest)
        nf = size(it%tri, 1)
        vm = 0.0_rk
        mm = 1.0_rk
        k = ct%row_k(p)
        ps = it%active(k)
        t = it%on_tri(k)
        call gather_columns(vm, ct%v, it%tri(:,t))
        do c = 1, nf
          mm(c) = ct%m(it%tri(c,t))
        end do
        dtan = 0.0_rk
        if (.not. on_planes) then
          call match_velocities(it%normal(:,k), ct%m(ps), ct%v(:,ps), mm, vm, it%area(:,k), &
                                it%share(:,k), it%friction, it%dn_sum(k), it%t_sum(:,k), dvs, dvm, closing, dn, dtan, &
                                held)
        else if (any(ct%plane_set(ct%row_node(:,p)) /= 0)) then
          proj(:,:,0) = ct%plane_proj(:,:,ct%plane_set(ps))
          do c = 1, 3
            proj(:,:,c) = ct%plane_proj(:,:,0)
            if (c <= nf) proj(:,:,c) = ct%plane_proj(:,:,ct%plane_set(it%tri(c,t)))
          end do
          call match_velocities(it%normal(:,k), ct%m(ps), ct%v(:,ps), mm, vm, it%area(:,k), &
                                it%share(:,k), 0.0_rk, it%dn_sum(k), it%t_sum(:,k), dvs, dvm, closing, dn, dtan, &
                                proj=proj)
        else
          call match_velocities(it%normal(:,k), ct%m(ps), ct%v(:,ps), mm, vm, it%area(:,k), &
                                it%share(:,k), 0.0_rk, it%dn_sum(k), it%t_sum(:,k), dvs, dvm, closing, dn, dtan)
        end if
        if (.not. closing) cycle
        it%dn_sum(k) = it%dn_sum(k) + dn
        it%t_sum(:,k) = it%t_sum(:,k) + dtan
        mismatch = max(mismatch, abs(dn), norm2(dtan))
        ! contact forces are internal: momentum is exchanged exactly, and
        ! whatever energy the matching dissipates shows in the energy error
        ct%v(:,ps) = ct%v(:,ps) + dvs
        ct%x(:,ps) = ct%x(:,ps) + dt*dvs
        do c = 1, nf
          pa = it%tri(c,t)
          ct%v(:,pa) = ct%v(:,pa) + dvm(:,c)
          ct%x(:,pa) = ct%x(:,pa) + dt*dvm(:,c)
        end do
      end associate
    end do
  end subroutine

  !> Whether a sweep that still changed mismatch has converged: within the
  !> interface's tolerance, or (tolerance 0) contact_relative_tolerance of
  !> the set's first change.
  pure logical function settled(mismatch, first_change, tolerance)
    real(rk), intent(in) :: mismatch, first_change, tolerance
    settled = mismatch <= merge(tolerance, contact_relative_tolerance*first_change, tolerance > 0.0_rk)
  end function

  !> Whether a node of rows a..b lies on a symmetry plane.
  logical function any_on_plane(ct, a, b)
    type(contact_t), intent(in) :: ct
    integer, intent(in) :: a, b
    integer :: q
    any_on_plane = .false.
    do q = a, b
      if (any(ct%plane_set(ct%row_node(:,q)) /= 0)) any_on_plane = .true.
    end do
  end function

  !> d projected onto the motions node's symmetry planes allow (plane_proj);
  !> d itself, bitwise, off the planes.
  pure function plane_direction(ct, node, d) result(pd)
    type(contact_t), intent(in) :: ct
    integer, intent(in) :: node
    real(rk), intent(in) :: d(3)
    real(rk) :: pd(3)
    pd = d
    if (ct%plane_set(node) /= 0) pd = matmul(ct%plane_proj(:,:,ct%plane_set(node)), d)
  end function

  !> The velocities of rows a..b's nodes at the start of a sweep.
  subroutine keep_row_velocities(ct, a, b)
    type(contact_t), intent(inout) :: ct
    integer, intent(in) :: a, b
    integer :: q, e
    do q = a, b
      do e = 0, 3
        ct%v_sweep(:, ct%row_node(e,q)) = ct%v(:, ct%row_node(e,q))
      end do
    end do
  end subroutine

  !> The largest change of a node velocity of rows a..b over the sweep.
  real(rk) function row_velocity_change(ct, a, b) result(change)
    type(contact_t), intent(in) :: ct
    integer, intent(in) :: a, b
    integer :: q, e
    change = 0
    do q = a, b
      do e = 0, 3
        change = max(change, norm2(ct%v(:,ct%row_node(e,q)) - ct%v_sweep(:,ct%row_node(e,q))))
      end do
    end do
  end function

  !> Row r's relative velocity d . (v_slave - v_master) along d (w(0) = -1).
  pure real(rk) function row_rate(v, node, w, d) result(rate)
    real(rk), intent(in) :: v(:,:), w(0:3), d(3)
    integer, intent(in) :: node(0:3)
    rate = -dot_product(d, w(1)*v(:,node(1)) + w(2)*v(:,node(2)) + w(3)*v(:,node(3)) - v(:,node(0)))
  end function

  !> A change lam along d of row r's slave node, with its masters' share:
  !> the velocities, and the positions by dt times them; on_planes: a node
  !> on a symmetry plane along d's projection (plane_direction).
  subroutine apply_row_change(ct, node, coef, d, lam, dt, on_planes)
    type(contact_t), intent(inout) :: ct
    integer, intent(in) :: node(0:3)
    real(rk), intent(in) :: coef(0:3), d(3), lam, dt
    logical, intent(in) :: on_planes
    integer :: p
    real(rk) :: dp(3)
    if (lam == 0.0_rk) return
    do p = 0, 3
      dp = d
      if (on_planes) dp = plane_direction(ct, node(p), d)
      ct%v(:,node(p)) = ct%v(:,node(p)) + (coef(p)*lam)*dp
      ct%x(:,node(p)) = ct%x(:,node(p)) + dt*(coef(p)*lam)*dp
    end do
  end subroutine

  !> The normal rows a..b of a joint set solved together (solve_normal_lcp,
  !> normal_rows_matrix). The accumulated changes so far (dn_sum) count:
  !> the solve is for the totals (>= 0). The changes are applied as the
  !> sweeps apply theirs (velocities, and positions by dt times them); the
  !> sweeps then add friction and what rounding left. A set of more than
  !> joint_solve_rows rows is solved only without friction (its
  !> alternation needs the joint friction solve, whose sets stop at
  !> joint_solve_rows), up to joint_dense_rows rows (a self-contact
  !> clamp's sets have up to 340, where the sweeps alone left 38 of its 92
  !> passes unconverged) with at most large_set_guesses guesses (each a
  !> dense solve of O(k^3)). A set the solve cannot settle is left to the
  !> sweeps. change: the largest normal velocity change the solve made;
  !> solved: whether it did.
  subroutine solve_set_normals(ct, a, b, frictionless, on_planes, dt, change, solved)
    type(contact_t), intent(inout) :: ct
    integer, intent(in) :: a, b
    logical, intent(in) :: frictionless      !< the pass's interfaces
    logical, intent(in) :: on_planes         !< nodes on symmetry planes move as the planes let them
    real(rk), intent(in) :: dt
    real(rk), intent(out) :: change
    logical, intent(out) :: solved
    integer, parameter :: nd = joint_dense_rows, large_set_guesses = 20
    real(rk) :: rhs(nd), lam(nd), lam0(nd), dl
    integer :: n, j, p, e
    change = 0
    solved = .false.
    n = b - a + 1
    if (n > nd) return
    if (n > joint_solve_rows .and. .not. frictionless) return
    do j = 1, n
      p = a + j - 1
      lam0(j) = ct%ifc(ct%row_ifc(p))%dn_sum(ct%row_k(p))
      rhs(j) = row_rate(ct%v, ct%row_node(:,p), ct%row_w(:,p), ct%row_nrm(:,p))
    end do
    if (on_planes) then
      do j = 1, n
        p = a + j - 1
        do e = 0, 3
          ct%lcp_dir(:,e,j) = plane_direction(ct, ct%row_node(e,p), ct%row_nrm(:,p))
        end do
      end do
      call normal_rows_matrix(n, nd, ct%row_node(:,a:b), ct%row_w(:,a:b), ct%row_coef(:,a:b), ct%row_nrm(:,a:b), &
                              ct%lcp_m, ct%lcp_dir(:,:,1:n))
    else
      call normal_rows_matrix(n, nd, ct%row_node(:,a:b), ct%row_w(:,a:b), ct%row_coef(:,a:b), ct%row_nrm(:,a:b), ct%lcp_m)
    end if
    ! for the totals: s = (b - M lam0) + M lam
    rhs(1:n) = rhs(1:n) - matmul(ct%lcp_m(1:n,1:n), lam0(1:n))
    if (n <= joint_solve_rows) then
      call solve_normal_lcp(n, nd, ct%lcp_m, rhs(1:n), lam(1:n), solved, ct%lcp_work, ct%lcp_free)
    else
      call solve_normal_lcp(n, nd, ct%lcp_m, rhs(1:n), lam(1:n), solved, ct%lcp_work, ct%lcp_free, &
                            max_guesses=large_set_guesses)
    end if
    if (.not. solved) return
    do j = 1, n
      p = a + j - 1
      dl = lam(j) - lam0(j)
      change = max(change, abs(dl))
      call apply_row_change(ct, ct%row_node(:,p), ct%row_coef(:,p), ct%row_nrm(:,p), dl, dt, on_planes)
      ct%ifc(ct%row_ifc(p))%dn_sum(ct%row_k(p)) = lam(j)
    end do
  end subroutine

  !> The rows a..b of a joint set with friction solved together, normals
  !> and friction (solve_friction_rows; up to joint_solve_rows rows): each
  !> row has its normal and two tangential velocities, the changes so far
  !> (dn_sum, t_sum) count (the solve is for the totals), and the changes
  !> are applied as the sweeps apply theirs. change as solve_set_normals;
  !> solved: whether it was (if not, nothing changed).
  subroutine solve_set_friction(ct, a, b, dt, change, solved)
    type(contact_t), intent(inout) :: ct
    integer, intent(in) :: a, b
    real(rk), intent(in) :: dt
    real(rk), intent(out) :: change
    logical, intent(out) :: solved
    integer, parameter :: ne = 3*joint_solve_rows
    integer :: n, j, p, ie, le, e_node(0:3,ne)
    real(rk) :: mu(joint_solve_rows), e_w(0:3,ne), e_coef(0:3,ne), b_rate(ne), x(ne), x0(ne), t1(3), t2(3), &
                dir(3,ne)
    change = 0
    solved = .false.
    n = b - a + 1
    if (n > joint_solve_rows) return
    ! three entries a row
    do j = 1, n
      p = a + j - 1
      associate (it => ct%ifc(ct%row_ifc(p)), k => ct%row_k(p))
        mu(j) = it%friction
        call tangent_basis(ct%row_nrm(:,p), t1, t2)
        le = 3*j - 2
        dir(:,le) = ct%row_nrm(:,p)
        dir(:,le+1) = t1
        dir(:,le+2) = t2
        x0(le) = it%dn_sum(k)
        x0(le+1) = dot_product(t1, it%t_sum(:,k))
        x0(le+2) = dot_product(t2, it%t_sum(:,k))
        do ie = 0, 2
          e_node(:,le+ie) = ct%row_node(:,p)
          e_w(:,le+ie) = ct%row_w(:,p)
          e_coef(:,le+ie) = ct%row_coef(:,p)
          b_rate(le+ie) = row_rate(ct%v, ct%row_node(:,p), ct%row_w(:,p), dir(:,le+ie))
        end do
      end associate
    end do
    call normal_rows_matrix(3*n, ne, e_node(:,1:3*n), e_w(:,1:3*n), e_coef(:,1:3*n), dir(:,1:3*n), ct%joint_m)
    call solve_friction_rows(n, ne, ct%joint_m, b_rate(1:3*n), x0(1:3*n), mu(1:n), x(1:3*n), solved, ct%joint_work)
    if (.not. solved) return
    do j = 1, n
      p = a + j - 1
      ie = 3*j - 2
      x(ie) = max(x(ie), 0.0_rk)
      do le = ie, ie + 2
        call apply_row_change(ct, ct%row_node(:,p), ct%row_coef(:,p), dir(:,le), x(le) - x0(le), dt, .false.)
        change = max(change, abs(x(le) - x0(le)))
      end do
      ct%ifc(ct%row_ifc(p))%dn_sum(ct%row_k(p)) = x(ie)
      ct%ifc(ct%row_ifc(p))%t_sum(:,ct%row_k(p)) = x(ie+1)*dir(:,ie+1) + x(ie+2)*dir(:,ie+2)
    end do
  end subroutine

  !> Finds the slave nodes of interface it behind a master triangle by at
  !> most depth_limit (stage_search) and corrects them (if move;
  !> stage_finish). In a cycle (dt > 0) match_passes matches the velocities
  !> in between, which undoes most of the penetration by momentum rather
  !> than by a jump; what then remains behind the surface is projected out
  !> along the normal (eq. 5), in bounded steps. With dt = 0 (before the
  !> first cycle, settling after erosion; stage_both) the slave nodes are
  !> only projected.
  subroutine detect(ct, it, depth_limit, move, dt, stage, n_found, deepest, worst, only)
    type(contact_t), intent(inout) :: ct
    type(interface_t), intent(inout) :: it
    real(rk), intent(in) :: depth_limit, dt
    logical, intent(in) :: move
    integer, intent(in) :: stage             !< stage_search, stage_finish, stage_both or stage_returns (the finish's returns alone)
    logical, intent(in), optional, allocatable :: only(:)   !< (slave nodes) if allocated: only these are looked for
    integer, intent(out) :: n_found, worst
    real(rk), intent(out) :: deepest
    real(rk) :: xa(3,3), n(3), dist, g(3), best_dist, best_n(3), best_g(3), vm(3,3), xa0(3,3), share(3), x_new(3), c_edge(3)
    integer :: nt, t, k, ps, best, iter, a, pa, kc, n_rec, nf
    real(rk) :: t_search, t_share
    logical :: separating
    real(rk) :: room
    nt = size(it%tri, 2)
    ! a face's nodes: 3 (a triangle, 3D) or 2 (a segment, 2D); xa(:,1:nf)
    nf = size(it%tri, 1)
    xa = 0
    n_found = it%n_pass
    deepest = 0
    worst = 0
    if (stage == stage_finish .or. stage == stage_returns) then
      if (move) call finish(stage == stage_finish)
      return
    end if
    n_found = 0
    it%n_pass = 0
    ! self-contact acts only on what crosses in a cycle (at rest a part's
    ! surface is behind the planes of many of its own faces)
    if (it%self .and. dt <= 0.0_rk) return
    it%passes = it%passes + 1
    if (dt > 0.0_rk) it%quiet_passes = it%quiet_passes + 1
    t_search = comms_wtime()
    ! the pass's boxes: of the triangles in the candidate lists (a slave
    ! node is only ever tested against its own), all of them after a full search
    if (lists_hold()) then
      do kc = 1, it%n_cand_tri
        t = it%cand_tri(kc)
        call triangle_box(t, depth_limit, it%box_lo(:,t), it%box_hi(:,t))
      end do
    else
      call full_search()
    end if
    it%dn_sum = 0
    it%t_sum = 0
    ! the cycle's figures (history, log) are the cycle pass's: a pass with
    ! dt = 0 (initial overlaps, settling after erosion) leaves them alone
    if (dt > 0.0_rk) then
      it%n_deep = 0
      it%normal_impulse = 0
      it%friction_impulse = 0
      it%master_impulse = 0
    end if
    ! ---- search: each of this rank's own slave nodes' master triangle, in
    ! ascending global id; what it found goes to every rank (share_found)
    call ensure(ct%rec_send, 2*rec_found*size(it%slave))   ! a valley node has two
    n_rec = 0
    do k = 1, size(it%slave)
      ps = it%slave(k)
      if (.not. it%mine(k)) cycle
      if (present(only)) then
        if (allocated(only)) then
          if (.not. only(k)) cycle
        end if
      end if
      if (it%self) call mark_ring(k, .true.)
      call nearest_behind(ps, .false., best, best_dist, best_n, best_g, separating, slot=k)
      if (it%self) call mark_ring(k, .false.)
      if (best == 0) cycle
      if (separating) then
        ! the paper releases it (no velocity change); it only goes back on the surface
        x_new = ct%x(:,ps)
        if (move) x_new = x_new + returned(along_planes(ps, -best_dist*best_n), allowance(ps))
        call add_record(k, best, kind_separating, best_dist, best_n, best_g, [0.0_rk, 0.0_rk, 0.0_rk], x_new)
        cycle
      end if
      call gather_columns(xa, ct%x, it%tri(:,best))
      xa0 = at_step_start(best)
      call face_shares(it%weights, xa(:,1:nf), ct%x(:,ps), best_g, best_n, xa0(:,1:nf), ct%x(:,ps) - dt*ct%v(:,ps), share)
      call add_record(k, best, kind_found, best_dist, best_n, best_g, share, ct%x(:,ps))
      ! in a valley of the master surface: the other face it is behind too
      if (.not. it%valleys .or. it%self .or. dt <= 0.0_rk) cycle
      call valley_partner(ps, k, best, best_n, t, dist, n, g)
      if (t == 0) cycle
      call gather_columns(xa, ct%x, it%tri(:,t))
      xa0 = at_step_start(t)
      call face_shares(it%weights, xa(:,1:nf), ct%x(:,ps), g, n, xa0(:,1:nf), ct%x(:,ps) - dt*ct%v(:,ps), share)
      call add_record(k, t, kind_valley, dist, n, g, share, ct%x(:,ps))
    end do
    t_share = comms_wtime()
    ct%seconds_search = ct%seconds_search + (t_share - t_search)
    call share_found(ct, it, n_rec, depth_limit, dt, n_found, deepest, worst)
    ct%seconds_exchange = ct%seconds_exchange + (comms_wtime() - t_share)
    if (dt > 0.0_rk) then
      ! nodes, not rows: a valley node has two
      it%n_active = n_found
      do k = 2, n_found
        if (it%slot(k) == it%slot(k-1)) it%n_active = it%n_active - 1
      end do
      it%max_depth = deepest
      if (it%n_deep > 0) then
        it%deep_total = it%deep_total + it%n_deep
        it%deep_passes = it%deep_passes + 1
      end if
    end if
    it%n_pass = n_found
    if (stage == stage_both .and. move) call finish(.true.)

  contains

    !> The cycle's impulses (what each node has received in all the
    !> passes), then what is left behind the surface goes back along the
    !> normal (eq. 5); the largest relative tangential velocity left at a
    !> contact point (slip).
    subroutine finish(impulses)
      logical, intent(in) :: impulses   !< the cycle's impulses too (else the returns alone, again)
      if (dt > 0.0_rk .and. impulses) then
        do k = 1, it%n_pass
          ps = it%active(k)
          it%normal_impulse = it%normal_impulse + ct%m(ps)*it%dn_sum(k)
          it%friction_impulse = it%friction_impulse + ct%m(ps)*norm2(it%t_sum(:,k))
          it%master_impulse = it%master_impulse - ct%m(ps)*(it%dn_sum(k)*it%normal(:,k) + it%t_sum(:,k))
          ct%impulse(ps) = ct%impulse(ps) + ct%m(ps)*it%dn_sum(k)
          do a = 1, nf
            pa = it%tri(a,it%on_tri(k))
            ct%impulse(pa) = ct%impulse(pa) + it%share(a,k)*ct%m(ps)*it%dn_sum(k)
          end do
        end do
        it%max_slip = 0
      end if
      ! onto the node's own triangle (every rank knows it)
      do k = 1, it%n_pass
        ps = it%active(k)
        t = it%on_tri(k)
        call gather_columns(xa, ct%x, it%tri(:,t))
        call face_projection(xa(:,1:nf), ct%x(:,ps), n, dist, g)
        room = allowance(ps)
        ! a valley node's second face: what is left of the same room
        if (k > 1) then
          if (it%slot(k-1) == it%slot(k)) room = it%room(k-1)
        end if
        if (dist < 0.0_rk) then
          if (it%seams .and. minval(g) < -edge_tolerance) then
            ! beyond the triangle's outline (a seam): onto its closest point
            call closest_on_face(xa(:,1:nf), ct%x(:,ps), c_edge, g)
            call put_back(ps, c_edge - ct%x(:,ps), room)
          else
            call put_back(ps, -dist*n, room)
          end if
        end if
        it%room(k) = room
        ! slip at the contact points that carry a normal impulse (a node whose
        ! push was all taken back by the later passes is not in contact)
        if (dt > 0.0_rk .and. impulses .and. it%dn_sum(k) > 0.0_rk) then
          g = max(it%area(:,k), 0.0_rk)/sum(max(it%area(:,k), 0.0_rk))
          vm(:,1) = face_velocity(t, g) - ct%v(:,ps)
          vm(:,1) = vm(:,1) - dot_product(vm(:,1), it%normal(:,k))*it%normal(:,k)
          it%max_slip = max(it%max_slip, norm2(vm(:,1)))
        end if
      end do
      ! back on one triangle's plane it may still be just behind a neighbour
      ! facing about the same way (a concave edge, e.g. a crater wall): twice
      ! more onto the shallowest such (not onto the side faces of a convex
      ! edge), by the node's owner, which has its candidates; a slave node is
      ! no master node here (self-contact has no such step), so the nodes'
      ! returns do not depend on each other
      if (it%self) return
      call ensure(ct%rec_send, rec_moved*(it%n_pass + size(it%slave)))
      n_rec = 0
      do k = 1, it%n_pass
        ps = it%active(k)
        if (.not. it%mine(it%slot(k))) cycle
        if (k < it%n_pass) then
          if (it%slot(k+1) == it%slot(k)) cycle     ! a valley node: after its second face
        end if
        room = it%room(k)
        x_new = ct%x(:,ps)
        do iter = 1, 2
          call nearest_behind(ps, .true., best, best_dist, best_n, best_g, separating, it%normal(:,k), it%slot(k))
          if (best == 0 .or. room <= 0.0_rk) exit
          call put_back(ps, -best_dist*best_n, room)
        end do
        it%exited(it%slot(k)) = .true.
        call exit_and_record(ps, it%slot(k), room, x_new)
      end do
      ! and the nodes not found: past the tip of a crack that an eroded
      ! element opened, inside the body beyond an edge and behind no face
      ! within its outline, a node is found by no plane (validation.md 4zj)
      do k = 1, size(it%slave)
        if (.not. it%mine(k)) cycle
        if (it%exited(k)) then
          it%exited(k) = .false.
          cycle
        end if
        ps = it%slave(k)
        x_new = ct%x(:,ps)
        room = return_room(ct%h(ps))
        call exit_and_record(ps, k, room, x_new)
      end do
      call share_positions(ct, n_rec)
    end subroutine

    !> The exit step (leave_element_under) of slave node ps in its slot, and
    !> its position queued for the other ranks if the pass moved it from
    !> x_before.
    subroutine exit_and_record(ps, slot, room, x_before)
      integer, intent(in) :: ps, slot
      real(rk), intent(inout) :: room
      real(rk), intent(in) :: x_before(3)
      call leave_element_under(ps, slot, room)
      if (all(ct%x(:,ps) == x_before)) return
      ct%rec_send(n_rec+1:n_rec+rec_moved) = [real(ps, rk), ct%x(:,ps)]
      n_rec = n_rec + rec_moved
    end subroutine

    !> Marks (or unmarks) slave node k's own neighbourhood, the nodes
    !> self-contact does not look at for it.
    subroutine mark_ring(k, on)
      integer, intent(in) :: k
      logical, intent(in) :: on
      integer :: j
      do j = it%ring_start(k), it%ring_start(k+1) - 1
        it%near(it%ring(j)) = on
      end do
    end subroutine

    !> Appends a found slave node's record for share_found: with the
    !> states of its node (at x) and of the face's (a segment's second node
    !> again in the third slot, which share_found does not read).
    subroutine add_record(k, t, kind, dist, n, g, share, x)
      integer, intent(in) :: k, t, kind
      real(rk), intent(in) :: dist, n(3), g(3), share(3), x(3)
      ps = it%slave(k)
      ct%rec_send(n_rec+1:n_rec+rec_found) = [real(k, rk), real(t, rk), real(kind, rk), dist, n, g, share, x, &
        ct%v(:,ps), ct%h(ps), ct%x(:,it%tri(1,t)), ct%x(:,it%tri(2,t)), ct%x(:,it%tri(nf,t)), &
        ct%v(:,it%tri(1,t)), ct%v(:,it%tri(2,t)), ct%v(:,it%tri(nf,t))]
      n_rec = n_rec + rec_found
    end subroutine

    !> The box a slave node must be in to be behind triangle t: its corners
    !> widened by reach, and the element under it (in a cycle, where known).
    subroutine triangle_box(t, reach, lo, hi)
      integer, intent(in) :: t
      real(rk), intent(in) :: reach
      real(rk), intent(out) :: lo(3), hi(3)
      real(rk) :: xt(3,3)
      call gather_columns(xt, ct%x, it%tri(:,t))
      lo = minval(xt(:,1:nf), dim=2)
      hi = maxval(xt(:,1:nf), dim=2)
      if (it%apex(t) > 0 .and. dt > 0.0_rk) then
        lo = min(lo, ct%x(:,it%apex(t)))
        hi = max(hi, ct%x(:,it%apex(t)))
      end if
      lo = lo - reach
      hi = hi + reach
    end subroutine

    !> Whether this rank has the current state of triangle t's nodes (and
    !> of the element under it): a triangle within reach of its share of
    !> the slave nodes always is (exchange_neighbourhood).
    logical function known(t)
      integer, intent(in) :: t
      integer :: a
      ! (a loop: any/all over a vector subscript allocate a temporary)
      known = .false.
      do a = 1, nf
        if (ct%fresh(it%tri(a,t)) /= ct%stamp) return
      end do
      if (it%apex(t) > 0) then
        if (ct%fresh(it%apex(t)) /= ct%stamp) return
      end if
      known = .true.
    end function

    !> How far slave node ps may be returned in this pass.
    real(rk) function allowance(ps)
      integer, intent(in) :: ps
      allowance = return_room(ct%h(ps))
    end function

    !> Return u of slave node ps as its symmetry planes let it move
    !> (return_on_planes: to the same plane, along the planes); u itself off them.
    function along_planes(ps, u) result(w)
      integer, intent(in) :: ps
      real(rk), intent(in) :: u(3)
      real(rk) :: w(3)
      w = u
      if (ct%plane_set(ps) /= 0) w = return_on_planes(u, ct%plane_proj(:,:,ct%plane_set(ps)))
    end function

    !> Moves slave node ps by u (along its planes), or as far along it as
    !> room allows; room shrinks by the distance moved.
    subroutine put_back(ps, u, room)
      integer, intent(in) :: ps
      real(rk), intent(in) :: u(3)
      real(rk), intent(inout) :: room
      real(rk) :: w(3)
      w = along_planes(ps, u)
      ct%x(:,ps) = ct%x(:,ps) + returned(w, room)
      room = max(room - norm2(w), 0.0_rk)
    end subroutine

    !> Whether the candidate lists still hold every triangle a slave node
    !> can be behind this pass: since the last full search no contact node
    !> has moved more than d, so a slave node and a triangle's box have
    !> closed by at most 2 d; the pass itself moves nodes by at most about
    !> twice the margin (velocity corrections, return to the surface).
    logical function lists_hold()
      real(rk) :: d2
      integer :: p, j
      lists_hold = .false.
      if (.not. it%tracking .or. dt <= 0.0_rk .or. it%reach_built < 0.0_rk) return
      d2 = 0
      if (ct%full_state .or. comms_size() == 1) then
        do p = 1, ct%n_nodes
          d2 = max(d2, sum((ct%x(:,p) - it%x_built(:,p))**2))
        end do
      else
        ! each rank's own nodes (the only ones every rank has current)
        do j = 1, size(ct%owned_pos)
          p = ct%owned_pos(j)
          d2 = max(d2, sum((ct%x(:,p) - it%x_built(:,p))**2))
        end do
        d2 = comms_max(d2)
      end if
      lists_hold = 3.0_rk*depth_limit + 2.0_rk*sqrt(d2) <= it%reach_built
    end function

    !> Bucket grid over the triangles' boxes widened by the margin and the
    !> skin, and each slave node's candidates: the triangles whose widened
    !> box holds it, ascending.
    subroutine full_search()
      real(rk) :: reach
      integer :: k, s, t, c, n_cand
      real(rk) :: own_lo(3), own_hi(3)
      reach = depth_limit
      if (it%tracking .and. dt > 0.0_rk) then
        ! the skin keeps the lists for the next passes; while the surfaces
        ! change every few cycles (erosion, conversion to particles) the
        ! next pass searches anew anyway, and the lists need only hold what
        ! the nodes can meet in this pass (lists_hold)
        reach = merge(depth_limit + it%skin, 3.0_rk*depth_limit, it%quiet_passes > quiet_passes_for_skin)
      end if
      ! the region of this rank's own slave nodes: only the triangles that
      ! reach into it go into the grid
      own_lo = huge(1.0_rk)
      own_hi = -huge(1.0_rk)
      do k = 1, size(it%slave)
        if (.not. it%mine(k)) cycle
        own_lo = min(own_lo, ct%x(:,it%slave(k)))
        own_hi = max(own_hi, ct%x(:,it%slave(k)))
      end do
      it%n_sub = 0
      do t = 1, nt
        if (.not. known(t)) cycle
        call triangle_box(t, reach, it%wide_lo(:,t), it%wide_hi(:,t))
        if (any(it%wide_hi(:,t) < own_lo) .or. any(it%wide_lo(:,t) > own_hi)) cycle
        call triangle_box(t, depth_limit, it%box_lo(:,t), it%box_hi(:,t))
        it%n_sub = it%n_sub + 1
        it%sub_tri(it%n_sub) = t
        it%sub_lo(:,it%n_sub) = it%wide_lo(:,t)
        it%sub_hi(:,it%n_sub) = it%wide_hi(:,t)
      end do
      call grid_build(it%grid, it%sub_lo(:,1:it%n_sub), it%sub_hi(:,1:it%n_sub))
      n_cand = 0
      it%cand_start(1) = 1
      do k = 1, size(it%slave)
        c = 0
        if (it%mine(k)) c = grid_cell(it%grid, ct%x(:,it%slave(k)))
        if (c > 0) then
          do s = it%grid%start(c), it%grid%start(c+1) - 1
            t = it%sub_tri(it%grid%items(s))
            if (any(ct%x(:,it%slave(k)) < it%wide_lo(:,t)) .or. any(ct%x(:,it%slave(k)) > it%wide_hi(:,t))) cycle
            n_cand = n_cand + 1
            if (n_cand > size(it%cand)) call ensure(it%cand, n_cand, keep=.true.)
            it%cand(n_cand) = t
          end do
        end if
        it%cand_start(k+1) = n_cand + 1
      end do
      do s = 1, n_cand
        it%tri_mark(it%cand(s)) = .true.
      end do
      it%n_cand_tri = 0
      do t = 1, nt
        if (.not. it%tri_mark(t)) cycle
        it%n_cand_tri = it%n_cand_tri + 1
        it%cand_tri(it%n_cand_tri) = t
        it%tri_mark(t) = .false.
      end do
      ! (where the lists are kept: lists_hold measures the moves from here)
      if (it%tracking .and. dt > 0.0_rk) it%x_built = ct%x
      it%reach_built = merge(reach, -1.0_rk, it%tracking .and. dt > 0.0_rk)
      it%full_searches = it%full_searches + 1
    end subroutine

    !> The master triangle slave node ps is behind (by at most depth_limit,
    !> its projection on the triangle). In a cycle: among the triangles it
    !> moves into, one it crossed during this step (no deeper than its
    !> approach over the step), the fastest approached; only when there is
    !> none, the fastest approached of the others (a node left a little
    !> behind by earlier cycles). At an edge or a corner of the master body
    !> the node is also, by rounding, just behind the side faces, but it did
    !> not cross them. A node moving away from every face is separating and
    !> left alone. Before the first cycle (dt = 0): the shallowest. Ties:
    !> the lowest triangle index.
    subroutine nearest_behind(ps, geometric, best, best_dist, best_n, best_g, separating, n_ref, slot)
      integer, intent(in) :: ps
      logical, intent(in) :: geometric     !< the shallowest, whatever the velocities
      real(rk), intent(in), optional :: n_ref(3)   !< only triangles facing within 60 degrees of it
      integer, intent(in) :: slot                  !< its slave index: look through its candidates
      integer, intent(out) :: best
      real(rk), intent(out) :: best_dist, best_n(3), best_g(3)
      logical, intent(out) :: separating
      real(rk) :: closing, best_closing, other_closing, other_dist, other_n(3), other_g(3), &
                  sep_dist, sep_n(3), front_dist
      integer :: other, sep
      integer :: t, s, first, last
      real(rk) :: xa(3,3), n(3), dist, g(3), c_near(3), seam_dist, seam_n(3), seam_g(3), xb(3,3,3), xs(3,3,3), xc(3,3,3,3)
      logical :: has(3), shares(3,3), sharp, off_face, own, hasc(3,3), taken
      integer :: verdict, seam, n_beside, a
      best = 0; other = 0; sep = 0; seam = 0
      seam_dist = -huge(1.0_rk)
      sep_dist = -huge(1.0_rk)
      separating = .false.
      best_dist = -huge(1.0_rk); other_dist = -huge(1.0_rk)
      best_closing = 0; other_closing = 0
      first = it%cand_start(slot)
      last = it%cand_start(slot+1) - 1
      front_dist = huge(1.0_rk)
      do s = first, last
        t = it%cand(s)
        if (.not. near_candidate(ps, t)) cycle
        if (it%self) then
          own = .false.
          do a = 1, nf
            own = own .or. it%near(it%tri(a,t))
          end do
          if (own) cycle   ! its own neighbourhood
        end if
        call gather_columns(xa, ct%x, it%tri(:,t))
        call face_projection(xa(:,1:nf), ct%x(:,ps), n, dist, g)
        if (dist >= 0.0_rk) then
          ! (on or in front of it, within its outline: below)
          if (all(g >= 0.0_rk)) front_dist = min(front_dist, dist)
          cycle
        end if
        ! the faces across its edges: for a sharp edge (a node that did not
        ! cross this plane in the step), or for a seam beyond an edge
        off_face = any(g < -edge_tolerance)
        sharp = .false.
        if (it%sharp_edges) sharp = .not. crossed(ps, t)
        if (sharp .or. (it%seams .and. off_face)) call faces_beside(t, xb, has)
        if (sharp) then
          ! each face across an edge shares the corners but the one opposite
          n_beside = 0
          do a = 1, nf
            if (.not. has(a)) cycle
            n_beside = n_beside + 1
            xs(:,:,n_beside) = xb(:,:,a)
            shares(:,n_beside) = [1, 2, 3] /= a
          end do
          ! (unless it is inside the element under the face: where a crack
          ! has closed over itself, the faces beside cross this one)
          if (face_beside_sharp_edge(xa(:,1:nf), n, g, xs(:,1:nf,:), shares(1:nf,:), n_beside, ct%x(:,ps), &
                                     edge_tolerance)) then
            if (.not. inside_element_under(ps, t, xa)) cycle
          else if (n_beside > 0) then
            ! (projecting past a face beside: the faces across its edges decide)
            call faces_across_beside(t, has, xc, hasc)
            if (face_beside_sharp_edge(xa(:,1:nf), n, g, xs(:,1:nf,:), shares(1:nf,:), n_beside, ct%x(:,ps), &
                                       edge_tolerance, xc, hasc)) then
              if (.not. inside_element_under(ps, t, xa)) cycle
            end if
          end if
        end if
        if (it%seams .and. off_face) then
          verdict = face_behind_surface(xa(:,1:nf), n, dist, g, xb, has, ct%x(:,ps), edge_tolerance)
          ! a node on a symmetry plane (2D: the axis or a symmetry line)
          ! beyond a face's edge on it is where the face and its mirror image
          ! meet, on the bisector of their fold, which face_behind_surface's
          ! halves of the seam share to rounding: in the seam
          if (verdict == behind_not) then
            if (beyond_mirrored_end(ps, t, g)) verdict = behind_seam
          end if
        else
          verdict = merge(behind_not, behind_face, off_face)
        end if
        if (verdict == behind_not) cycle
        if (verdict == behind_seam) then
          ! in the seam of a dented surface (no face has it within its
          ! outline): the contact is with the triangle's closest point,
          ! along the way to it; taken only when no face has the node
          if (it%self .or. dist < -depth_limit) cycle
          ! (on a symmetry plane the way to the closest point, longer than
          ! to the plane, is held to the margin too)
          call seam_contact(xa(:,1:nf), ct%x(:,ps), depth_limit, ct%sym_planes(ps) /= 0, c_near, g, n, dist, taken)
          if (.not. taken .or. dist <= seam_dist) cycle
          seam = t; seam_dist = dist; seam_n = n; seam_g = g
          cycle
        end if
        if (dist < -depth_limit) then
          ! deeper than any approach in a step: only inside the element under
          ! the face (a face erosion exposed under a node already inside)
          if (geometric .or. dt <= 0.0_rk .or. it%apex(t) == 0) cycle
          if (.not. inside_element_under(ps, t, xa)) cycle
        end if
        if (present(n_ref)) then
          if (dot_product(n, n_ref) < 0.5_rk) cycle
        end if
        if (dt > 0.0_rk .and. .not. geometric) then
          closing = approach(ps, t, n, g)
          if (closing <= 0.0_rk) then
            ! self-contact: only a node in contact in the last pass (no
            ! false contact with the part's own far side)
            if (it%self) then
              if (.not. it%touched(slot)) cycle
            end if
            ! behind but already moving out: remembered, to be put back on the surface
            if (dist > sep_dist) then
              sep = t; sep_dist = dist; sep_n = n
            end if
            cycle
          end if
          if (-dist > closing*dt + residual_tolerance*it%h_mean) then
            if (it%self) cycle
            ! behind, but deeper than this step's approach
            if (closing < other_closing .or. (closing == other_closing .and. dist <= other_dist)) cycle
            other = t; other_closing = closing; other_dist = dist; other_n = n; other_g = g
            cycle
          end if
          if (closing < best_closing .or. (closing == best_closing .and. dist <= best_dist)) cycle
          best_closing = closing
        else if (dist <= best_dist) then
          cycle
        end if
        best = t; best_dist = dist; best_n = n; best_g = g
      end do
      ! The surface point nearest a node tells whether it is inside
      ! (Baerentzen and Aanaes 2005), and a face the node is on or in front
      ! of, within its outline, is front_dist away: a face or a seam farther
      ! than that is not the nearest, and the node, behind its plane, is
      ! outside there (beside a convex corner or a knife edge, a node on one
      ! face is behind the plane of the next; returned to it, the node went
      ! through the nearer face, validation.md 4zn). So are taken only if
      ! no farther than front_dist: the shallowest face when settling
      ! (positions alone), a face behind which the node is deeper than the
      ! step's approach, and a seam. (Within the step's approach a node on
      ! one face of a corner that the step took behind the other is in
      ! contact with it.)
      ! Where the node's projection falls inside no face it is in front of
      ! (beside a knife edge), its nearest surface point is on an edge or a
      ! vertex, and outside there it bounds the same way (computed only
      ! when it could decide).
      if (.not. it%self) then
        if ((dt <= 0.0_rk .and. best /= 0 .and. -best_dist <= front_dist) .or. &
            (other /= 0 .and. -other_dist <= front_dist) .or. &
            (best == 0 .and. seam /= 0 .and. -seam_dist <= front_dist) .or. &
            (sep /= 0 .and. -sep_dist <= front_dist)) &
          front_dist = min(front_dist, outside_distance(ps, slot))
      end if
      if (dt <= 0.0_rk .and. best /= 0) then
        if (-best_dist > front_dist) best = 0
      end if
      if (other /= 0) then
        if (-other_dist > front_dist) other = 0
      end if
      ! (not in self-contact: a node there is behind faces of its own body
      ! by nature, and only one in contact in the last pass separates)
      if (sep /= 0 .and. .not. it%self) then
        if (-sep_dist > front_dist) sep = 0
      end if
      if (best == 0 .and. other /= 0) then
        best = other; best_dist = other_dist; best_n = other_n; best_g = other_g
      else if (best == 0 .and. seam /= 0 .and. -seam_dist <= front_dist) then
        best = seam; best_dist = seam_dist; best_n = seam_n; best_g = seam_g
        ! moving out of the seam: as a separating node, only put back
        if (dt > 0.0_rk .and. .not. geometric) separating = approach(ps, seam, seam_n, seam_g) <= 0.0_rk
      else if (best == 0 .and. sep /= 0) then
        best = sep; best_dist = sep_dist; best_n = sep_n
        separating = .true.
      end if
      if (best == 0 .and. .not. geometric .and. dt > 0.0_rk) &
        call inside_at_feature(ps, slot, best, best_dist, best_n, best_g, separating)
    end subroutine

    !> Whether slave node ps is strictly inside the element under face t
    !> (corners xa; the element's corner opposite, it%apex(t), known in a
    !> cycle on eroding surfaces): not on another of its faces.
    logical function inside_element_under(ps, t, xa)
      integer, intent(in) :: ps, t
      real(rk), intent(in) :: xa(3,3)
      inside_element_under = .false.
      if (dt <= 0.0_rk) return
      inside_element_under = in_element_under(ct%x(:,ps), t, xa, edge_tolerance)
    end function

    !> Whether point p is inside the element under face t (corners xa)
    !> by more than tolerance in every barycentric coordinate (false where
    !> the face's apex is not known).
    logical function in_element_under(p, t, xa, tolerance)
      real(rk), intent(in) :: p(3)
      integer, intent(in) :: t
      real(rk), intent(in) :: xa(3,3), tolerance
      real(rk) :: lam(4)
      in_element_under = .false.
      if (it%apex(t) == 0) return
      call element_coordinates(xa(:,1:nf), ct%x(:,it%apex(t)), p, lam)
      call mirrored_coordinates([it%tri(1:nf,t), it%apex(t)], lam)
      in_element_under = all(lam(1:nf+1) > tolerance)
    end function

    !> Slave node ps, still inside the master body after the returns onto
    !> planes, goes to the nearest point of its candidate triangles, as far
    !> as room allows: at a vertex or an edge where the faces of a jagged
    !> crater meet, behind several of their planes, no plane's return takes
    !> it out (validation.md 4zj). Inside: strictly inside the element under
    !> one of those triangles, or, within the search depth (every face that
    !> near is a candidate, so the nearest point is the surface's) from a
    !> vertex or an edge nearest to it, behind the vertex's
    !> angle-weighted normal (the edge's faces' mean normal; Baerentzen and
    !> Aanaes 2005), which also sees the elements at a vertex that have no
    !> face on the surface. Inside the body, the nearest point of its
    !> surface is out of it.
    subroutine leave_element_under(ps, slot, room)
      integer, intent(in) :: ps, slot
      real(rk), intent(inout) :: room
      real(rk) :: xa(3,3), c(3), g(3), c_best(3), g_best(3), d, d_best
      integer :: s, t, t_best, n_feature
      logical :: inside
      if (room <= 0.0_rk) return
      inside = .false.
      d_best = huge(1.0_rk)
      t_best = 0
      do s = it%cand_start(slot), it%cand_start(slot+1) - 1
        t = it%cand(s)
        if (.not. near_candidate(ps, t)) cycle
        call gather_columns(xa, ct%x, it%tri(:,t))
        ! (strictly: the apex itself has a coordinate 0)
        if (.not. inside) inside = in_element_under(ct%x(:,ps), t, xa, 0.0_rk)
        call closest_on_face(xa(:,1:nf), ct%x(:,ps), c, g)
        d = norm2(c - ct%x(:,ps))
        if (d < d_best) then
          d_best = d
          c_best = c
          g_best = g
          t_best = t
        end if
      end do
      if (t_best == 0) return
      n_feature = count(g_best(1:nf) > 0.0_rk)
      ! an element at the nearest feature's nodes can reach past the faces
      ! there (a tangled vertex of a fractured crater wall), with no face on the surface
      ! (not for a node on a symmetry plane: its way out is in the plane,
      ! which the nearest point of the faces on one side need not be)
      if (.not. inside .and. d_best <= depth_limit .and. ct%sym_planes(ps) == 0) &
        inside = in_element_at(t_best, g_best, ct%x(:,ps))
      if (.not. inside .and. n_feature < nf .and. d_best > 0.0_rk .and. d_best <= depth_limit) &
        inside = .not. outside_at_feature(ps, slot, t_best, g_best, c_best)
      if (.not. inside) return
      ! where master elements overlap (debris of the target hinged on an
      ! edge and turned into each other), the nearest face point can lie
      ! inside another element: the nearest one that is outside all of them
      if (in_candidate_element(slot, c_best) .or. in_element_at(t_best, g_best, c_best)) &
        call nearest_point(ps, slot, .true., t_best, g_best, c_best, t, g, d)
      call put_back(ps, c_best - ct%x(:,ps), room)
    end subroutine

    !> Whether slave node ps is outside the master body at the vertex or
    !> edge c of its candidate triangle t nearest to it (g: the feature's
    !> area coordinates, those > 0): in front of the feature's
    !> angle-weighted normal (the edge's faces' mean normal; Baerentzen and
    !> Aanaes 2005). A feature on a symmetry plane also has the faces'
    !> mirror images, which leave the normal's part in the plane.
    logical function outside_at_feature(ps, slot, t_near, g_near, c) result(outside)
      integer, intent(in) :: ps, slot, t_near
      real(rk), intent(in) :: g_near(3), c(3)
      real(rk) :: xa(3,3), n(3), dist, g(3), wn(3)
      integer :: s, t, a, b, corner, planes, on_planes
      logical :: at_feature
      wn = 0.0_rk
      planes = -1
      on_planes = 0
      do b = 1, nf
        if (g_near(b) <= 0.0_rk) cycle
        planes = iand(planes, ct%sym_planes(it%tri(b,t_near)))
        if (ct%sym_planes(it%tri(b,t_near)) == planes) on_planes = it%tri(b,t_near)
      end do
      do s = it%cand_start(slot), it%cand_start(slot+1) - 1
        t = it%cand(s)
        if (.not. near_candidate(ps, t)) cycle
        corner = 0
        at_feature = .true.
        do b = 1, nf
          if (g_near(b) <= 0.0_rk) cycle
          at_feature = at_feature .and. any(it%tri(1:nf,t) == it%tri(b,t_near))
          do a = 1, nf
            if (it%tri(a,t) == it%tri(b,t_near)) corner = a
          end do
        end do
        if (.not. at_feature) cycle
        call gather_columns(xa, ct%x, it%tri(:,t))
        call face_projection(xa(:,1:nf), ct%x(:,ps), n, dist, g)
        if (count(g_near(1:nf) > 0.0_rk) == 1 .and. nf == 3) n = corner_angle(xa, corner)*n
        wn = wn + n
      end do
      ! (the projector of the feature's node whose planes are the feature's)
      if (planes /= 0 .and. on_planes /= 0) then
        if (ct%sym_planes(on_planes) == planes) wn = plane_direction(ct, on_planes, wn)
      end if
      outside = dot_product(ct%x(:,ps) - c, wn) >= 0.0_rk
    end function

    !> The distance from slave node ps to the nearest point of its
    !> candidate triangles when that point is a vertex or an edge and ps
    !> is outside the body there (outside_at_feature), within the search
    !> depth (every face that near is a candidate); huge otherwise.
    real(rk) function outside_distance(ps, slot) result(d)
      integer, intent(in) :: ps, slot
      real(rk), parameter :: no_feature(3) = 0.0_rk
      real(rk) :: c(3), g(3)
      integer :: t
      call nearest_point(ps, slot, .false., 0, no_feature, c, t, g, d)
      if (t == 0 .or. d > depth_limit) then
        d = huge(1.0_rk)
      else if (d > 0.0_rk) then
        ! (within a face's outline the face loop has seen its side)
        if (count(g(1:nf) > 0.0_rk) == nf) then
          d = huge(1.0_rk)
        else if (.not. outside_at_feature(ps, slot, t, g, c)) then
          d = huge(1.0_rk)
        end if
      end if
    end function

    !> Point p strictly inside (beyond rounding) an element of the eroding
    !> master part at a node of triangle t where g > 0 (the feature nearest
    !> to it); only elements whose nodes' states are current here.
    logical function in_element_at(t, g, p)
      integer, intent(in) :: t
      real(rk), intent(in) :: g(3), p(3)
      real(rk) :: xa(3,3), xd(3), lam(4)
      integer :: a, k, e, c
      logical :: current
      in_element_at = .false.
      if (it%master_part == 0) return
      do a = 1, nf
        if (g(a) <= 0.0_rk) cycle
        do k = ct%node_tet_ptr(it%tri(a,t)), ct%node_tet_ptr(it%tri(a,t)+1) - 1
          e = ct%node_tet(k)
          if (.not. ct%tet_alive(e) .or. ct%tet_part(e) /= it%master_part) cycle
          current = .true.
          do c = 1, nf + 1
            current = current .and. ct%fresh(ct%tet(c,e)) == ct%stamp
          end do
          if (.not. current) cycle
          call gather_columns(xa(:,1:nf), ct%x, ct%tet(1:nf,e))
          xd = ct%x(:,ct%tet(nf+1,e))
          call element_coordinates(xa(:,1:nf), xd, p, lam)
          call mirrored_coordinates(ct%tet(1:nf+1,e), lam)
          in_element_at = all(lam(1:nf+1) > overlap_tolerance)
          if (in_element_at) return
        end do
      end do
    end function

    !> An element's coordinates lam of a point (corners: nodes) as the
    !> mirrored body has them: where the face opposite a corner lies in a
    !> symmetry plane and the point is on it (to rounding), the element's
    !> mirror image continues there, and that coordinate bounds nothing (a
    !> node in the plane inside the in-plane face of an element is inside
    !> the body; validation.md 4zo).
    subroutine mirrored_coordinates(nodes, lam)
      integer, intent(in) :: nodes(:)
      real(rk), intent(inout) :: lam(:)
      integer :: c, k
      integer :: others(3)
      do c = 1, nf + 1
        if (abs(lam(c)) > overlap_tolerance) cycle
        others(1:nf) = pack(nodes(1:nf+1), [(k /= c, k = 1, nf + 1)])
        if (on_symmetry_plane(ct%sym_planes, others(1:nf))) lam(c) = huge(1.0_rk)
      end do
    end subroutine

    !> Point p strictly inside (beyond rounding of the area coordinates) an
    !> element under one of slot's candidate triangles.
    logical function in_candidate_element(slot, p)
      integer, intent(in) :: slot
      real(rk), intent(in) :: p(3)
      real(rk) :: xa(3,3)
      integer :: s, t
      in_candidate_element = .true.
      do s = it%cand_start(slot), it%cand_start(slot+1) - 1
        t = it%cand(s)
        if (it%apex(t) == 0 .or. .not. known(t)) cycle
        call gather_columns(xa, ct%x, it%tri(:,t))
        if (in_element_under(p, t, xa, overlap_tolerance)) return
      end do
      in_candidate_element = .false.
    end function

    !> The nearest point c to slave node ps of its candidate triangles, on
    !> triangle t_out at its area coordinates g_out, d its distance; with
    !> outside, the nearest that is in no element under them nor at the
    !> nodes of feature g_near of triangle t_near (in_element_at). t_out =
    !> 0 (c unchanged) if there is none.
    subroutine nearest_point(ps, slot, outside, t_near, g_near, c, t_out, g_out, d_out)
      integer, intent(in) :: ps, slot, t_near
      logical, intent(in) :: outside
      real(rk), intent(in) :: g_near(3)
      real(rk), intent(inout) :: c(3)
      integer, intent(out) :: t_out
      real(rk), intent(out) :: g_out(3), d_out
      real(rk) :: xa(3,3), q(3), g(3), d
      integer :: s, t
      d_out = huge(1.0_rk)
      t_out = 0
      g_out = 0
      do s = it%cand_start(slot), it%cand_start(slot+1) - 1
        t = it%cand(s)
        if (.not. near_candidate(ps, t)) cycle
        call gather_columns(xa, ct%x, it%tri(:,t))
        call closest_on_face(xa(:,1:nf), ct%x(:,ps), q, g)
        d = norm2(q - ct%x(:,ps))
        if (d >= d_out) cycle
        if (outside) then
          if (in_candidate_element(slot, q) .or. in_element_at(t_near, g_near, q)) cycle
        end if
        d_out = d
        c = q
        t_out = t
        g_out = g
      end do
    end subroutine

    !> Slave node ps behind no face the search takes, yet inside an element
    !> of the master body at the vertex or edge of the surface nearest to
    !> it (within the search depth): where the faces at a vertex of a
    !> crushed crater wall leave it beyond every outline, or an element
    !> there reaches past them, no plane finds it and only the bounded exit
    !> step acts, which the node's velocity outruns. Matched instead at the
    !> nearest surface point out of the body (t, area coordinates g), along
    !> the way to it (n), as a seam node is; moving out, only put back. Not
    !> for a node on a symmetry plane (leave_element_under).
    subroutine inside_at_feature(ps, slot, t, dist, n, g, separating)
      integer, intent(in) :: ps, slot
      integer, intent(out) :: t
      real(rk), intent(out) :: dist, n(3), g(3)
      logical, intent(out) :: separating
      real(rk), parameter :: no_feature(3) = 0.0_rk
      real(rk) :: c(3), d, g_near(3)
      integer :: t_near
      t = 0; dist = 0; n = 0; g = 0
      separating = .false.
      if (it%master_part == 0 .or. it%self .or. ct%sym_planes(ps) /= 0) return
      call nearest_point(ps, slot, .false., 0, no_feature, c, t_near, g_near, d)
      if (t_near == 0 .or. d <= 0.0_rk .or. d > depth_limit) return
      if (.not. in_element_at(t_near, g_near, ct%x(:,ps))) return
      t = t_near
      g = g_near
      if (in_candidate_element(slot, c) .or. in_element_at(t_near, g_near, c)) &
        call nearest_point(ps, slot, .true., t_near, g_near, c, t, g, d)
      if (t == 0 .or. d <= 0.0_rk) then
        t = 0
        return
      end if
      dist = -d
      n = (c - ct%x(:,ps))/d
      separating = approach(ps, t, n, g) <= 0.0_rk
    end subroutine

    !> Candidate triangle t of a slave node at ps can hold it: ps in its box,
    !> its nodes' states current, ps not one of its nodes (the box first:
    !> most candidates fail it, and it reads one array).
    logical function near_candidate(ps, t)
      integer, intent(in) :: ps, t
      near_candidate = .false.
      if (any(ct%x(:,ps) < it%box_lo(:,t)) .or. any(ct%x(:,ps) > it%box_hi(:,t))) return
      if (.not. known(t)) return
      if (any(it%tri(:,t) == ps)) return
      near_candidate = .true.
    end function

    !> Whether slave node ps lies on the symmetry plane (2D: line or axis)
    !> of an edge (a segment's end) of face t that its projection
    !> (coordinates g) falls beyond: where the face and its mirror image
    !> meet, on the bisector of their fold.
    logical function beyond_mirrored_end(ps, t, g)
      integer, intent(in) :: ps, t
      real(rk), intent(in) :: g(3)
      integer :: a, p
      beyond_mirrored_end = .false.
      do a = 1, nf
        if (g(a) >= -edge_tolerance) cycle
        p = edge_plane(t, a)
        if (p == 0) cycle
        beyond_mirrored_end = abs(dot_product(ct%plane(1:3,p), ct%x(:,ps)) - ct%plane(4,p)) <= 1.0e-9_rk*it%h_mean
        if (beyond_mirrored_end) return
      end do
    end function

    !> The symmetry plane that the edge of face t opposite corner a (2D: the
    !> segment's end opposite node a) lies on and corner a does not (a face
    !> in a symmetry plane has no mirror image): the lowest such, 0 if none.
    integer function edge_plane(t, a)
      integer, intent(in) :: t, a
      integer :: bits
      if (nf == 3) then
        bits = iand(ct%sym_planes(it%tri(mod(a,3)+1,t)), ct%sym_planes(it%tri(mod(a+1,3)+1,t)))
      else
        bits = ct%sym_planes(it%tri(3-a,t))
      end if
      bits = iand(bits, not(ct%sym_planes(it%tri(a,t))))
      edge_plane = 0
      if (bits /= 0) edge_plane = trailz(bits) + 1
    end function

    !> The second face of a valley (&contact valleys) that slave node ps is
    !> behind besides its triangle best (normal best_n): a face of its
    !> candidates sharing an edge with best, within the search depth, with
    !> the node's projection on it, that the node approaches, and that folds
    !> concavely against best by more than valley_cos (each one's centroid
    !> in front of the other's plane): outside such a fold is in front of
    !> both planes, so matching one face leaves the node drifting through
    !> the other. The fastest approached; ties: the deeper, then the lowest
    !> index. t2 = 0: none.
    subroutine valley_partner(ps, slot, best, best_n, t2, dist2, n2, g2)
      integer, intent(in) :: ps, slot, best
      real(rk), intent(in) :: best_n(3)
      integer, intent(out) :: t2
      real(rk), intent(out) :: dist2, n2(3), g2(3)
      real(rk) :: xa(3,3), n(3), dist, g(3), closing, best_closing, c_best(3), c_t(3), fold
      integer :: s, t, a2, shared
      t2 = 0; dist2 = 0; n2 = 0; g2 = 0
      best_closing = 0
      call gather_columns(xa, ct%x, it%tri(:,best))
      c_best = sum(xa(:,1:nf), dim=2)/real(nf, rk)
      fold = 1.0e-3_rk*it%h_mean
      do s = it%cand_start(slot), it%cand_start(slot+1) - 1
        t = it%cand(s)
        if (t == best) cycle
        if (any(ct%x(:,ps) < it%box_lo(:,t)) .or. any(ct%x(:,ps) > it%box_hi(:,t))) cycle
        if (.not. known(t)) cycle
        if (any(it%tri(:,t) == ps)) cycle
        call gather_columns(xa, ct%x, it%tri(:,t))
        call face_projection(xa(:,1:nf), ct%x(:,ps), n, dist, g)
        if (dist >= 0.0_rk .or. dist < -depth_limit) cycle
        if (any(g < -edge_tolerance)) cycle
        if (dot_product(n, best_n) > valley_cos) cycle
        ! sharing an edge (3D) or a node (2D)
        shared = 0
        do a2 = 1, nf
          if (any(it%tri(:,t) == it%tri(a2,best))) shared = shared + 1
        end do
        if (shared < nf - 1) cycle
        c_t = sum(xa(:,1:nf), dim=2)/real(nf, rk)
        if (dot_product(best_n, c_t - c_best) <= fold) cycle
        if (dot_product(n, c_best - c_t) <= fold) cycle
        closing = approach(ps, t, n, g)
        if (closing <= 0.0_rk .or. closing < best_closing) cycle
        if (closing == best_closing .and. dist >= dist2) cycle
        t2 = t; dist2 = dist; n2 = n; g2 = g; best_closing = closing
      end do
    end subroutine

    !> How fast slave node ps approaches triangle t along its normal n at
    !> its projection (area coordinates g, clipped onto the triangle).
    real(rk) function approach(ps, t, n, g)
      integer, intent(in) :: ps, t
      real(rk), intent(in) :: n(3), g(3)
      real(rk) :: gc(3)
      gc = max(g, 0.0_rk)/sum(max(g, 0.0_rk))
      approach = dot_product(n, face_velocity(t, gc) - ct%v(:,ps))
    end function

    !> The velocity of face t's point at coordinates g (a segment: g(1:2)).
    function face_velocity(t, g) result(v)
      integer, intent(in) :: t
      real(rk), intent(in) :: g(3)
      real(rk) :: v(3)
      if (nf == 3) then
        v = g(1)*ct%v(:,it%tri(1,t)) + g(2)*ct%v(:,it%tri(2,t)) + g(3)*ct%v(:,it%tri(3,t))
      else
        v = g(1)*ct%v(:,it%tri(1,t)) + g(2)*ct%v(:,it%tri(2,t))
      end if
    end function

    !> Whether slave node ps was in front of triangle t's plane at the start
    !> of the step (positions x - dt v): it crossed the plane in this step.
    !> Not in a pass without a step (dt = 0).
    logical function crossed(ps, t)
      integer, intent(in) :: ps, t
      real(rk) :: n0(3), d0, g0(3), x0(3,3)
      crossed = .false.
      if (dt <= 0.0_rk) return
      x0 = at_step_start(t)
      call face_projection(x0(:,1:nf), ct%x(:,ps) - dt*ct%v(:,ps), n0, d0, g0)
      crossed = d0 >= 0.0_rk
    end function

    !> Where triangle t's corners were at the start of the step, x - dt v
    !> (dt = 0: where they are).
    function at_step_start(t) result(x0)
      integer, intent(in) :: t
      real(rk) :: x0(3,3)
      integer :: a
      x0 = 0
      do a = 1, nf
        x0(:,a) = ct%x(:,it%tri(a,t)) - dt*ct%v(:,it%tri(a,t))
      end do
    end function

    !> For each face beside triangle t (as faces_beside has them, has), in
    !> the same order: the faces across its edges (xc(:,:,c,k): across the
    !> edge opposite its corner c; hasc(c,k) false: none this rank has
    !> current, or a mirror image's, which has no neighbours here).
    subroutine faces_across_beside(t, has, xc, hasc)
      integer, intent(in) :: t
      logical, intent(in) :: has(3)
      real(rk), intent(out) :: xc(3,3,3,3)
      logical, intent(out) :: hasc(3,3)
      integer :: a, c, k, tb, tc
      xc = 0
      hasc = .false.
      k = 0
      do a = 1, nf
        if (.not. has(a)) cycle
        k = k + 1
        tb = neighbour_across(it, t, a)
        if (tb <= 0) cycle
        do c = 1, nf
          tc = neighbour_across(it, tb, c)
          if (tc <= 0) cycle
          hasc(c,k) = known(tc)
          if (hasc(c,k)) call gather_columns(xc(:,:,c,k), ct%x, it%tri(:,tc))
        end do
      end do
    end subroutine

    !> The triangles across the three edges of triangle t (xb(:,:,a): across
    !> the edge opposite corner a; has(a) false: a rim, or one this rank has
    !> not current), or in 2D the segments across the two ends of segment t
    !> (xb(:,1:2,a): across the end opposite node a). Every rank has current
    !> those near its own slave nodes: the neighbourhood reaches a face's
    !> extent beyond them.
    subroutine faces_beside(t, xb, has)
      integer, intent(in) :: t
      real(rk), intent(out) :: xb(3,3,3)
      logical, intent(out) :: has(3)
      integer :: a, tb, p, k
      xb = 0
      has = .false.
      do a = 1, nf
        tb = neighbour_across(it, t, a)
        has(a) = tb > 0
        if (has(a)) has(a) = known(tb)
        if (has(a)) call gather_columns(xb(:,:,a), ct%x, it%tri(:,tb))
        if (tb > 0) cycle
        ! an edge on a symmetry plane (2D: an end on the axis or a symmetry
        ! line) is no rim: the surface goes on as the face's mirror image
        ! (its corners in reverse order: counter-clockwise from outside)
        p = edge_plane(t, a)
        if (p == 0) cycle
        has(a) = .true.
        do k = 1, nf
          xb(:,k,a) = mirrored(ct%x(:,it%tri(nf+1-k,t)), ct%plane(:,p))
        end do
      end do
    end subroutine
  end subroutine

  !> Keeps the velocities of this rank's own contact nodes: v(n-1/2) before
  !> the velocity update (which = 1) or v(n+1/2) just before the contact pass
  !> (which = 2), for contact_work.
  subroutine contact_keep_velocities(ct, dom, which)
    type(contact_t), intent(inout) :: ct
    type(domain_t), intent(in) :: dom
    integer, intent(in) :: which
    integer :: k
    if (ct%n_interfaces == 0) return
    do k = 1, size(ct%owned_pos)
      if (which == 1) then
        ct%v_prev(:,k) = dom%nd_v(:, ct%local(ct%owned_pos(k)))
      else
        ct%v_pre(:,k) = dom%nd_v(:, ct%local(ct%owned_pos(k)))
      end if
    end do
  end subroutine

  !> The largest distance between two nodes of a triangle of the surfaces
  !> (or its node and the element's fourth corner) over the triangles whose
  !> nodes are all on this rank (every triangle is whole on the rank of its
  !> element), and of an eroding body's element whose nodes are all on this
  !> rank, at the nodes' current positions: ct%size_local, what
  !> exchange_neighbourhood widens by. Called at the start of the step,
  !> when every node here (ghosts too) is current.
  subroutine contact_extent(ct, dom)
    type(contact_t), intent(inout) :: ct
    type(domain_t), intent(in) :: dom
    integer :: i, k, t, a, c(4), nc
    real(rk) :: e
    if (ct%n_interfaces == 0 .or. ct%full_state .or. comms_size() == 1) return
    e = 0
    do i = 1, ct%n_interfaces
      associate (it => ct%ifc(i))
        if (.not. it%local_tri_valid) then
          it%local_tri = pack([(t, t = 1, size(it%tri, 2))], [(all(ct%local(it%tri(:,t)) > 0) .and. &
                              (it%apex(t) == 0 .or. ct%local(max(it%apex(t), 1)) > 0), t = 1, size(it%tri, 2))])
          it%local_tri_valid = .true.
        end if
        do k = 1, size(it%local_tri)
          t = it%local_tri(k)
          nc = size(it%tri, 1)
          c(1:nc) = ct%local(it%tri(:,t))
          if (it%apex(t) > 0) then
            nc = nc + 1
            c(nc) = ct%local(it%apex(t))
          end if
          e = max(e, widest(c(1:nc)))
        end do
      end associate
    end do
    ! and the eroding bodies' elements whole here: the exit step and the
    ! search test a node against every element at a surface vertex
    ! (in_element_at), which reach as far from the node as they are large
    do t = 1, ct%n_tets
      if (.not. ct%tet_alive(t)) cycle
      nc = size(ct%tet, 1)
      do a = 1, nc
        c(a) = ct%local(ct%tet(a,t))
      end do
      if (any(c(1:nc) == 0)) cycle
      e = max(e, widest(c(1:nc)))
    end do
    ct%size_local = sqrt(e)

  contains

    !> The largest squared distance between two of the local nodes c.
    real(rk) function widest(c) result(e2)
      integer, intent(in) :: c(:)
      integer :: a, b
      e2 = 0
      do a = 1, size(c) - 1
        do b = a + 1, size(c)
          e2 = max(e2, sum((dom%nd_x(:,c(a)) - dom%nd_x(:,c(b)))**2))
        end do
      end do
    end function
  end subroutine

  !> Work of the contact impulses of the pass on this rank's own nodes into
  !> the exact accumulator acc: m dv . (v(n-1/2) + v(n+1/2)) / 2, the form
  !> in which an impulse enters the central-difference kinetic energy
  !> (KE(n+1/2) - KE(n-1/2) = sum m (v(n+1/2) - v(n-1/2)) . the mean of the
  !> two), so that KE + IE - contact work is conserved as the element
  !> forces' part is.
  subroutine contact_work(ct, dom, acc)
    type(contact_t), intent(in) :: ct
    type(domain_t), intent(in) :: dom
    integer(i8), intent(inout) :: acc(0:exact_limbs)
    integer :: k, n
    real(rk) :: dv(3)
    if (ct%n_interfaces == 0) return
    do k = 1, size(ct%owned_pos)
      n = ct%local(ct%owned_pos(k))
      dv = dom%nd_v(:,n) - ct%v_pre(:,k)
      if (all(dv == 0.0_rk)) cycle
      call exact_add(acc, 0.5_rk*dom%nd_mass(n)*dot_product(dv, ct%v_prev(:,k) + dom%nd_v(:,n)))
    end do
  end subroutine

  !> Contact pressure of every contact node in the last pass (into
  !> ct%pressure): the normal impulse it received over the step and its
  !> tributary area, a third of each adjacent contact face that is wholly in
  !> contact (all three nodes loaded; so an edge node does not count the
  !> free side faces), or of every adjacent face for a node that has none;
  !> in 2D half of each adjacent segment's area (axisymmetric: per
  !> revolution).
  subroutine contact_pressure(ct, dom)
    type(contact_t), intent(inout) :: ct
    type(domain_t), intent(in) :: dom
    integer :: f, pass
    real(rk) :: node_area      !< a node's share of the face's area (a third of a triangle, half a segment)
    ct%pressure = 0
    ct%work_area = 0
    if (ct%dt_last <= 0.0_rk) return       ! before the first pass
    ! the faces' current areas: every contact node (an output step only)
    call gather_state(ct, dom)
    do pass = 1, 2
      do f = 1, size(ct%faces, 2)
        if (pass == 1) then
          if (any(ct%impulse(ct%faces(:,f)) <= 0.0_rk)) cycle
        else
          if (.not. any(ct%impulse(ct%faces(:,f)) > 0.0_rk .and. ct%pressure(ct%faces(:,f)) <= 0.0_rk)) cycle
        end if
        if (size(ct%faces, 1) == 3) then
          associate (a => ct%x(:,ct%faces(1,f)), b => ct%x(:,ct%faces(2,f)), c => ct%x(:,ct%faces(3,f)))
            node_area = norm2([(b(2)-a(2))*(c(3)-a(3)) - (b(3)-a(3))*(c(2)-a(2)), &
                               (b(3)-a(3))*(c(1)-a(1)) - (b(1)-a(1))*(c(3)-a(3)), &
                               (b(1)-a(1))*(c(2)-a(2)) - (b(2)-a(2))*(c(1)-a(1))])/6.0_rk
          end associate
        else
          ! 2D: half the segment, per unit depth, or (axisymmetric) of the
          ! cone it sweeps in a full revolution, as the masses are
          associate (a => ct%x(:,ct%faces(1,f)), b => ct%x(:,ct%faces(2,f)))
            node_area = 0.5_rk*norm2(b - a)
            if (dom%geometry == geometry_axisymmetric) node_area = node_area*pi*(a(1) + b(1))
          end associate
        end if
        if (pass == 1) then
          ct%pressure(ct%faces(:,f)) = ct%pressure(ct%faces(:,f)) + node_area
        else
          ! only the loaded nodes that no wholly loaded face reached
          where (ct%impulse(ct%faces(:,f)) > 0.0_rk .and. ct%pressure(ct%faces(:,f)) <= 0.0_rk) &
            ct%work_area(ct%faces(:,f)) = ct%work_area(ct%faces(:,f)) + node_area
        end if
      end do
    end do
    where (ct%pressure <= 0.0_rk) ct%pressure = ct%work_area
    where (ct%pressure > 0.0_rk) ct%pressure = ct%impulse/(ct%dt_last*ct%pressure)
  end subroutine

  !> x and v of every contact node, from their owners, into ct (collective).
  subroutine gather_state(ct, dom)
    type(contact_t), intent(inout) :: ct
    type(domain_t), intent(in) :: dom
    integer :: k, p, n
    ct%stamp = ct%stamp + 1
    ct%fresh = ct%stamp
    if (comms_size() == 1) then
      do p = 1, ct%n_mesh
        ct%x(:,p) = dom%nd_x(:,ct%local(p))
        ct%v(:,p) = dom%nd_v(:,ct%local(p))
        if (ct%returns(p)) ct%h(p) = node_altitude(dom, ct%local(p))
      end do
      return
    end if
    do k = 1, size(ct%owned_pos)
      n = ct%local(ct%owned_pos(k))
      ct%send(7*k-6:7*k-4) = dom%nd_x(:,n)
      ct%send(7*k-3:7*k-1) = dom%nd_v(:,n)
      ct%send(7*k) = huge(1.0_rk)
      if (ct%returns(ct%owned_pos(k))) ct%send(7*k) = node_altitude(dom, n)
    end do
    call comms_allgatherv_real(ct%send, ct%counts, ct%recv)
    do k = 1, ct%n_mesh
      p = ct%gather_pos(k)
      ct%x(:,p) = ct%recv(7*k-6:7*k-4)
      ct%v(:,p) = ct%recv(7*k-3:7*k-1)
      ct%h(p) = ct%recv(7*k)
    end do
  end subroutine

  !> The state of the contact nodes this rank needs for its share of the
  !> search, not of all (collective; several ranks): its own contact nodes;
  !> the slave nodes of its share, from their owners; and every contact
  !> node within reach of them, i.e. within the box of its share's slave
  !> nodes widened by the search reach, the largest extent of a triangle
  !> and the element under it (at the start of the step, size_local, plus
  !> what its nodes can move since) and what the pass can move the nodes.
  !> Those nodes are fresh (ct%fresh = ct%stamp); the search uses no other.
  !> vmax: in, the fastest of the other contact nodes (the particles);
  !> out, the fastest contact node (every rank).
  subroutine exchange_neighbourhood(ct, dom, dt, vmax)
    type(contact_t), intent(inout) :: ct
    type(domain_t), intent(in) :: dom
    real(rk), intent(in) :: dt
    real(rk), intent(inout) :: vmax
    integer :: k, p, n, q, i, me, np, pass, r
    real(rk) :: lo(3), hi(3), widen, reach
    np = comms_size()
    me = comms_rank()
    ct%stamp = ct%stamp + 1
    do k = 1, size(ct%owned_pos)
      p = ct%owned_pos(k)
      n = ct%local(p)
      ct%x(:,p) = dom%nd_x(:,n)
      ct%v(:,p) = dom%nd_v(:,n)
      if (ct%returns(p)) ct%h(p) = node_altitude(dom, n)
      ct%fresh(p) = ct%stamp
      vmax = max(vmax, norm2(ct%v(:,p)))
    end do
    vmax = comms_max(vmax)
    ! the slave nodes this rank owns to the ranks that search for them
    do pass = 1, 2
      if (pass == 2) call start_fill()
      do i = 1, ct%n_interfaces
        do k = 1, size(ct%ifc(i)%slave)
          p = ct%ifc(i)%slave(k)
          q = ct%ifc(i)%searcher(k)
          if (q == me .or. ct%local(p) == 0) cycle
          if (ct%local(p) <= dom%n_owned_nodes) call put(pass, q, p)
        end do
      end do
    end do
    call swap()
    ! every rank's region: the box of its share's slave nodes
    lo = huge(1.0_rk)
    hi = -huge(1.0_rk)
    reach = 0
    do i = 1, ct%n_interfaces
      associate (it => ct%ifc(i))
        do k = 1, size(it%slave)
          if (.not. it%mine(k)) cycle
          lo = min(lo, ct%x(:,it%slave(k)))
          hi = max(hi, ct%x(:,it%slave(k)))
        end do
        reach = max(reach, 2.0_rk*vmax*dt + 0.05_rk*it%h_mean + it%skin)
      end associate
    end do
    ct%regions(6*me+1:6*me+6) = [lo, hi]
    call comms_allgatherv_real(ct%regions(6*me+1:6*me+6), ct%region_counts, ct%regions)
    widen = reach + comms_max(ct%size_local) + 8.0_rk*vmax*dt
    ! this rank's contact nodes within the others' widened regions
    do pass = 1, 2
      if (pass == 2) call start_fill()
      do k = 1, size(ct%owned_pos)
        p = ct%owned_pos(k)
        do q = 0, np - 1
          if (q == me) cycle
          r = 6*q
          if (any(ct%x(:,p) < ct%regions(r+1:r+3) - widen) .or. any(ct%x(:,p) > ct%regions(r+4:r+6) + widen)) cycle
          call put(pass, q, p)
        end do
      end do
    end do
    call swap()

  contains

    subroutine put(pass, q, p)
      integer, intent(in) :: pass, q, p
      if (pass == 1) then
        ct%x_counts(q) = ct%x_counts(q) + rec_state
      else
        ct%x_send(ct%rec_next(q)+1:ct%rec_next(q)+rec_state) = [real(p, rk), ct%x(:,p), ct%v(:,p), ct%h(p)]
        ct%rec_next(q) = ct%rec_next(q) + rec_state
      end if
    end subroutine

    subroutine start_fill()
      ct%rec_next(0) = 0
      do q = 1, np - 1
        ct%rec_next(q) = ct%rec_next(q-1) + ct%x_counts(q-1)
      end do
      call ensure(ct%x_send, sum(ct%x_counts))
    end subroutine

    !> Sends what was put, takes in what came: the nodes' states, fresh.
    subroutine swap()
      integer :: j
      call comms_alltoall_counts(ct%x_counts, ct%x_rcounts)
      call ensure(ct%x_recv, sum(ct%x_rcounts))
      call comms_alltoallv_real(ct%x_send, ct%x_counts, ct%x_recv, ct%x_rcounts)
      do j = 0, sum(ct%x_rcounts) - rec_state, rec_state
        p = nint(ct%x_recv(j+1))
        ct%x(:,p) = ct%x_recv(j+2:j+4)
        ct%v(:,p) = ct%x_recv(j+5:j+7)
        ct%h(p) = ct%x_recv(j+8)
        ct%fresh(p) = ct%stamp
      end do
      ct%x_counts = 0
    end subroutine
  end subroutine

  !> Smallest altitude of the elements at owned node n (huge when none is
  !> left).
  pure real(rk) function node_altitude(dom, n) result(h)
    type(domain_t), intent(in) :: dom
    integer, intent(in) :: n
    integer :: k
    h = huge(1.0_rk)
    do k = dom%nd_el_ptr(n), dom%nd_el_ptr(n+1) - 1
      h = min(h, dom%el_h(dom%nd_el(k)))
    end do
  end function

  !> The corrected x and v back into this rank's nodes (owned and ghost)
  !> that the pass knew.
  subroutine scatter_state(ct, dom)
    type(contact_t), intent(in) :: ct
    type(domain_t), intent(inout) :: dom
    integer :: p, n
    do p = 1, ct%n_nodes
      n = ct%local(p)
      if (n == 0 .or. ct%fresh(p) /= ct%stamp) cycle
      dom%nd_x(:,n) = ct%x(:,p)
      dom%nd_v(:,n) = ct%v(:,p)
    end do
  end subroutine
end module udar_contact
