!> Contact surfaces from the deck and the mesh (global domain, every rank
!> alike): master triangles oriented out of their body, slave nodes, and
!> the list of contact nodes whose state the contact pass needs.
module udar_contact_setup
  use udar_kinds, only: rk
  use udar_config, only: config_t, contact_cfg_t, overlap_move, eroded_particles
  use udar_gmsh, only: gmsh_mesh_t
  use udar_domain, only: domain_t
  use udar_input_errors, only: input_errors_t
  use udar_deck, only: deck_where
  use udar_setup, only: find_group, group_list
  use udar_strings, only: itoa, to_lower
  use udar_comms, only: comms_rank, comms_size
  use udar_contact_model, only: joint_solve_rows, joint_dense_rows, feature_edges, contact_t, interface_t, size_interface_work, surface_neighbours, self_neighbourhoods, on_symmetry_plane, &
                                assign_slaves, mark_returns
  use udar_contact_faces, only: points_inside_elements
  use udar_contact_kernels, only: constrained_projection
  implicit none
  private
  public :: build_contact, tet_face, tri_face, element_face, contact_edges, exterior_faces

  !> local nodes of the face opposite each tet corner
  integer, parameter :: tet_face(3,4) = reshape([2,3,4, 1,4,3, 1,2,4, 1,3,2], [3,4])
  !> 2D: local nodes of the edge opposite each corner of a triangle, in its
  !> counter-clockwise order (the outward normal of edge a -> b is (dy, -dx))
  integer, parameter :: tri_face(2,3) = reshape([2,3, 3,1, 1,2], [2,3])

contains

  !> The local nodes of the face of an element of `corners` corners opposite
  !> its corner f: a tetrahedron's triangle (tet_face) or a 2D triangle's
  !> edge (tri_face), counter-clockwise seen from outside.
  pure function element_face(corners, f) result(nodes)
    integer, intent(in) :: corners, f
    integer :: nodes(corners - 1)
    if (corners == 4) then
      nodes = tet_face(:,f)
    else
      nodes = tri_face(:,f)
    end if
  end function

  subroutine build_contact(cfg, mesh, glob, ct, errs)
    type(config_t), intent(in) :: cfg
    type(gmsh_mesh_t), intent(in) :: mesh
    type(domain_t), intent(in) :: glob
    type(contact_t), intent(out) :: ct
    type(input_errors_t), intent(inout) :: errs
    integer, allocatable :: face(:,:), face_part(:), master(:,:), slave(:), tri_all(:,:), cn_of(:), sym_planes(:)
    type(interface_t), allocatable :: ifc(:)
    integer :: k, n_err0, nf, n_ifc, i, mark_count, m_part, s_part, e, nv, n_contacts, ip
    type(contact_cfg_t) :: cs
    logical, allocatable :: part_erodes(:)
    logical, allocatable :: is_contact(:), face_used(:), m_body(:), s_body(:), own_done(:)
    character(len=:), allocatable :: mname, sname, face_word

    ct%n_interfaces = 0
    allocate(ct%ifc(0), ct%gidx(0))
    n_contacts = 0
    if (allocated(cfg%contacts)) n_contacts = size(cfg%contacts)
    ! a part whose eroded elements become particles: its particles are kept
    ! out of its own remaining body too (one interface, after the deck's)
    allocate(ct%part_converts(size(cfg%parts)), source=.false.)
    allocate(ct%part_voids(size(cfg%parts)), source=.false.)
    do e = 1, glob%n_elems
      if (glob%mat(glob%el_mat(e))%eroded == eroded_particles) ct%part_converts(glob%el_part(e)) = .true.
    end do
    if (n_contacts == 0 .and. .not. any(ct%part_converts)) return
    n_err0 = errs%count()
    call exterior_faces(glob, face, face_part, nf)
    sym_planes = symmetry_planes(glob, ct%plane)
    nv = glob%corners - 1
    face_word = merge('triangle', 'segment ', nv == 3)
    ! the boundary on a symmetry plane (2D: the axis or a symmetry line)
    ! bounds no material (the body continues across it): no contact face.
    ! (Until 0.9.3 3D kept them in two-part contacts: a slave node on the
    ! plane was behind such a face by rounding every pass, which took the
    ! node from the crater's faces it was really behind; the Fig. 4 deck's
    ! rod nodes on the plane went 0.13 h into the plate.)
    k = 0
    do e = 1, nf
      if (on_symmetry_plane(sym_planes, face(:,e))) cycle
      k = k + 1
      face(:,k) = face(:,e)
      face_part(k) = face_part(e)
    end do
    nf = k
    allocate(face_used(nf), source=.false.)
    allocate(own_done(size(cfg%parts)), source=.false.)
    ! (at most: the contacts, their symmetric twins, the converting parts; trimmed below)
    n_ifc = count(ct%part_converts)
    if (n_contacts > 0) n_ifc = n_ifc + n_contacts + count(cfg%contacts%symmetric)
    allocate(ifc(n_ifc))
    i = 0
    do k = 1, n_contacts
      cs = cfg%contacts(k)
      associate (c => cfg%contacts(k))
        call surface(c%master, 'master', k, master, mname, m_part, m_body)
        call surface(c%slave, 'slave', k, tri_all, sname, s_part, s_body)
        if (errs%count() > n_err0) cycle
        if (to_lower(c%master) == to_lower(c%slave)) then
          ! self-contact (its faces on symmetry planes were left out above, as everywhere)
          i = i + 1
          call make_interface(ifc(i), master, unique_nodes(master), master, sname//'_on_itself')
          ifc(i)%self = .true.
          ifc(i)%master_part = eroding_part(m_part)
          ifc(i)%slave_part = eroding_part(s_part)
          cycle
        end if
        slave = unique_nodes(tri_all)
        i = i + 1
        call make_interface(ifc(i), master, slave, tri_all, sname//'_on_'//mname)
        call mark_start_inside(ifc(i), m_body)
        ifc(i)%master_body = m_body
        ifc(i)%master_part = eroding_part(m_part)
        ifc(i)%slave_part = eroding_part(s_part)
        if (c%symmetric) then
          i = i + 1
          call make_interface(ifc(i), tri_all, unique_nodes(master), master, mname//'_on_'//sname)
          call mark_start_inside(ifc(i), s_body)
          ifc(i)%master_body = s_body
          ifc(i)%master_part = eroding_part(s_part)
          ! the two directions are matched together, in one set of passes
          ifc(i)%partner = i - 1
          ifc(i-1)%partner = i
          ifc(i)%slave_part = eroding_part(m_part)
        end if
        if (c%voids) call void_parts(k, m_part, s_part)
        ! each converting part of the contact, once: its particles on its own surface
        call own_particles(m_part, master, m_body)
        call own_particles(s_part, tri_all, s_body)
      end associate
    end do
    if (errs%count() > n_err0) return
    ! a converting part that no contact names (a Taylor bar): its particles
    ! on its own surface all the same, with the &contact defaults
    cs = contact_cfg_t()
    do ip = 1, size(cfg%parts)
      if (.not. ct%part_converts(ip) .or. own_done(ip)) cycle
      call take_faces(face_part(1:nf) == ip, master, m_body)
      call own_particles(ip, master, m_body)
    end do
    n_ifc = i
    if (size(ifc) > n_ifc) ifc = ifc(1:n_ifc)

    ! contact nodes: every node of a master triangle or a slave set, and
    ! every node of an eroding part (any may come to the surface)
    allocate(is_contact(glob%n_nodes), source=.false.)
    do i = 1, n_ifc
      is_contact(reshape(ifc(i)%tri, [size(ifc(i)%tri)])) = .true.
      is_contact(ifc(i)%slave) = .true.
    end do
    allocate(part_erodes(size(cfg%parts)), source=.false.)
    do i = 1, n_ifc
      if (ifc(i)%master_part > 0) part_erodes(ifc(i)%master_part) = .true.
      if (ifc(i)%slave_part > 0) part_erodes(ifc(i)%slave_part) = .true.
    end do
    do e = 1, glob%n_elems
      if (part_erodes(glob%el_part(e))) is_contact(glob%el_conn(e,:)) = .true.
    end do
    mark_count = count(is_contact)
    ct%gidx = pack([(k, k = 1, glob%n_nodes)], is_contact)
    allocate(cn_of(glob%n_nodes), source=0)
    cn_of(ct%gidx) = [(k, k = 1, mark_count)]
    do i = 1, n_ifc
      ifc(i)%tri = reshape(cn_of(reshape(ifc(i)%tri, [size(ifc(i)%tri)])), shape(ifc(i)%tri))
      ifc(i)%slave_tri = reshape(cn_of(reshape(ifc(i)%slave_tri, [size(ifc(i)%slave_tri)])), shape(ifc(i)%slave_tri))
      ifc(i)%slave = cn_of(ifc(i)%slave)
    end do
    ct%n_nodes = mark_count
    do i = 1, n_ifc
      if (ifc(i)%self) call self_neighbourhoods(ifc(i), ct%n_nodes)
    end do
    do i = 1, n_ifc
      allocate(ifc(i)%x_built(3, ct%n_nodes))
    end do
    ! every face of a contact surface once (tributary areas of the nodes)
    ct%faces = face(:, pack([(k, k = 1, nf)], face_used))
    ct%faces = reshape(cn_of(reshape(ct%faces, [size(ct%faces)])), shape(ct%faces))
    ! (faces left out of a self-contact surface, on a symmetry plane, may hold non-contact nodes)
    ct%faces = ct%faces(:, pack([(k, k = 1, size(ct%faces, 2))], all(ct%faces > 0, dim=1)))
    ! the tetrahedra of the eroding parts, their neighbours across each face;
    ! the faces of the other surfaces stay as they are
    call eroding_topology(glob, part_erodes, cn_of, ct)
    ct%fixed_faces = face(:, pack([(k, k = 1, nf)], face_used .and. .not. part_erodes(face_part(1:nf))))
    ct%fixed_faces = reshape(cn_of(reshape(ct%fixed_faces, [size(ct%fixed_faces)])), shape(ct%fixed_faces))
    ct%fixed_faces = ct%fixed_faces(:, pack([(k, k = 1, size(ct%fixed_faces, 2))], all(ct%fixed_faces > 0, dim=1)))
    allocate(ct%impulse(ct%n_nodes), ct%pressure(ct%n_nodes), ct%work_area(ct%n_nodes), source=0.0_rk)
    ct%n_interfaces = n_ifc
    call move_alloc(ifc, ct%ifc)
    ct%m = glob%nd_mass(ct%gidx)
    allocate(ct%x(3, ct%n_nodes), ct%v(3, ct%n_nodes), ct%v_sweep(3, ct%n_nodes))
    allocate(ct%joint_m(3*joint_solve_rows, 3*joint_solve_rows), ct%joint_work(3*joint_solve_rows, 3*joint_solve_rows+1))
    allocate(ct%lcp_m(joint_dense_rows, joint_dense_rows), ct%lcp_work(joint_dense_rows, joint_dense_rows+1), source=0.0_rk)
    allocate(ct%lcp_dir(3, 0:3, joint_dense_rows), source=0.0_rk)
    allocate(ct%lcp_free(joint_dense_rows), source=.false.)
    allocate(ct%node_row(ct%n_nodes), source=0)
    allocate(ct%h(ct%n_nodes), source=huge(1.0_rk))
    ct%x = glob%nd_x0(:, ct%gidx)
    ct%x0 = ct%x
    ct%v = glob%nd_v(:, ct%gidx)
    ct%sym_planes = sym_planes(ct%gidx)
    call plane_projectors(ct)
    do i = 1, n_ifc
      ! the face across each edge, by contact-node index (after the renumbering)
      if (ct%ifc(i)%seams .or. ct%ifc(i)%sharp_edges) call surface_neighbours(ct%ifc(i), ct%x0)
      if (ct%ifc(i)%edges) call contact_edges(ct%ifc(i), ct%x0)
      call assign_slaves(ct%ifc(i), ct%x0, comms_rank(), comms_size())
    end do
    call mark_returns(ct)
    ! particles (eroded = 'particles') join the contact nodes as they are made
    ct%n_mesh = ct%n_nodes
    allocate(ct%particle_part(0))

  contains

    !> The interface that keeps part ip's particles out of its own remaining
    !> body (the surface tri, the body's parts body), with the settings cs
    !> (contact k's, or the defaults), if ip converts and has none yet. Without it a part's failed
    !> material goes through the part itself: the target's crater debris
    !> through the target, a projectile's eroded front overrun by its rear.
    subroutine own_particles(ip, tri, body)
      integer, intent(in) :: ip
      integer, intent(in) :: tri(:,:)
      logical, intent(in) :: body(:)
      integer :: no_nodes(0), no_tri(nv,0)
      if (ip == 0) return
      if (.not. ct%part_converts(ip) .or. own_done(ip)) return
      own_done(ip) = .true.
      i = i + 1
      call make_interface(ifc(i), tri, no_nodes, no_tri, trim(cfg%parts(ip)%group)//'_particles_on_itself')
      ifc(i)%edges = .false.
      ifc(i)%valleys = .false.
      ifc(i)%own_particles = .true.
      allocate(ifc(i)%start_inside(0))
      ifc(i)%master_body = body
      ifc(i)%master_part = eroding_part(ip)
      ifc(i)%slave_part = eroding_part(ip)
    end subroutine

    !> The triangles of a part's boundary (name of a part) or of a physical
    !> surface group, in global node indices, oriented out of their body.
    subroutine surface(name, role, k, tri, label, part, body)
      character(len=*), intent(in) :: name, role
      integer, intent(in) :: k
      integer, allocatable, intent(out) :: tri(:,:)
      character(len=:), allocatable, intent(out) :: label
      integer, intent(out) :: part           !< the part whose boundary it is, 0 for a surface group
      logical, allocatable, intent(out) :: body(:)   !< (parts) the parts whose boundary the triangles are
      integer :: ip, ig
      label = trim(name)
      part = 0
      do ip = 1, size(cfg%parts)
        if (to_lower(trim(cfg%parts(ip)%group)) == to_lower(trim(name))) exit
      end do
      if (ip <= size(cfg%parts)) then
        call take_faces(face_part(1:nf) == ip, tri, body)
        part = ip
        return
      end if
      ig = find_group(mesh, trim(name), mesh%dim - 1)
      if (ig > 0) then
        call group_triangles(ig, tri, body)
        if (size(tri, 2) == 0) call errs%add(deck_where(cfg, 'contact', k, role)//": "// &
          trim(merge('surface group', 'curve group  ', nv == 3))//" '"//trim(name)//"' has no "//trim(face_word)// &
          ' on the boundary of the mesh'//trim(merge(' (off the axis and symmetry lines)', ' (off the symmetry planes)        ', &
          nv == 2)))
        return
      end if
      allocate(tri(nv,0))
      allocate(body(size(cfg%parts)), source=.false.)
      call errs%add(deck_where(cfg, 'contact', k, role)//": '"//trim(name)//"' is neither a part nor a "// &
        'physical '//trim(merge('surface', 'curve  ', nv == 3))//' group of '//trim(cfg%mesh%file)//' (parts: '// &
        group_list(mesh, mesh%dim)//'; '//trim(merge('surface', 'curve  ', nv == 3))//' groups: '// &
        group_list(mesh, mesh%dim - 1)//')')
    end subroutine

    !> The exterior faces (of any part) whose nodes are all nodes of the
    !> triangles of physical surface group ig (2D: of the lines of physical
    !> curve group ig).
    subroutine group_triangles(ig, tri, body)
      integer, intent(in) :: ig
      integer, allocatable, intent(out) :: tri(:,:)
      logical, allocatable, intent(out) :: body(:)
      logical, allocatable :: in_group(:)
      integer, allocatable :: node_g(:)
      integer :: t, a
      call mesh_to_global(mesh, glob, node_g)
      allocate(in_group(glob%n_nodes), source=.false.)
      do t = 1, mesh%n_facets
        if (mesh%facet_group(t) /= ig) cycle
        do a = 1, size(mesh%facet, 2)
          if (node_g(mesh%facet(t,a)) > 0) in_group(node_g(mesh%facet(t,a))) = .true.
        end do
      end do
      call take_faces([(all(in_group(face(:,t))), t = 1, nf)], tri, body)
    end subroutine

    !> Which slave nodes start inside the master body (an element of the
    !> parts the master faces are faces of, to rounding, not one of its
    !> corners): only these are initial overlaps. Behind a face's plane
    !> with the projection on it is not enough: ahead of a sharp edge or
    !> corner of a coarse master, a node in front of the body is behind the
    !> planes of faces beyond it. Global node indices; in_body: the parts
    !> whose boundary the master surface is.
    subroutine mark_start_inside(it, in_body)
      type(interface_t), intent(inout) :: it
      logical, intent(in) :: in_body(:)
      integer :: e
      allocate(it%start_inside(size(it%slave)))
      call points_inside_elements(glob%el_conn, glob%nd_x0, pack([(e, e = 1, glob%n_elems)], in_body(glob%el_part)), &
                                  glob%nd_x0(:, it%slave), it%start_inside, exclude=it%slave)
    end subroutine

    !> &contact voids of contact k (master part mp, slave part sp; 0 a
    !> surface group): the eroding parts among them keep closed voids; an
    !> input error where neither erodes, a part's eroded elements become
    !> particles, or the mesh is 2D (3D tetrahedra only for now).
    subroutine void_parts(k, mp, sp)
      integer, intent(in) :: k, mp, sp
      integer :: j, ip
      if (glob%corners /= 4) then
        call errs%add(deck_where(cfg, 'contact', k, 'voids')//': closed voids are for 3D meshes only (for now)')
        return
      end if
      if (eroding_part(mp) == 0 .and. eroding_part(sp) == 0) then
        call errs%add(deck_where(cfg, 'contact', k, 'voids')//': neither part of the contact erodes '// &
                      '(&material eps_erode): there are no voids to keep closed')
        return
      end if
      do j = 1, 2
        ip = eroding_part(merge(mp, sp, j == 1))
        if (ip == 0) cycle
        if (ct%part_converts(ip)) then
          call errs%add(deck_where(cfg, 'contact', k, 'voids')//": part '"//trim(cfg%parts(ip)%group)// &
                        "' makes particles of its eroded elements (&material eroded = 'particles'): "// &
                        "they fill the hole; voids are for eroded = 'free_nodes'")
          cycle
        end if
        ct%part_voids(ip) = .true.
      end do
    end subroutine

    !> Part ip if its material erodes (its boundary changes), else 0.
    integer function eroding_part(ip)
      integer, intent(in) :: ip
      eroding_part = 0
      if (ip == 0) return
      if (glob%mat(glob%el_mat(findloc(glob%el_part, ip, dim=1)))%eps_erode > 0.0_rk) eroding_part = ip
    end function

    !> The exterior faces selected, remembered as contact faces, and the
    !> parts they bound.
    subroutine take_faces(selected, tri, body)
      logical, intent(in) :: selected(:)
      integer, allocatable, intent(out) :: tri(:,:)
      logical, allocatable, intent(out) :: body(:)
      integer :: f
      tri = face(:, pack([(f, f = 1, nf)], selected))
      face_used = face_used .or. selected
      allocate(body(size(cfg%parts)), source=.false.)
      body(face_part(pack([(f, f = 1, nf)], selected))) = .true.
    end subroutine

    subroutine make_interface(it, tri, slave_nodes, slave_tri, label)
      type(interface_t), intent(inout) :: it
      integer, intent(in) :: tri(:,:), slave_nodes(:), slave_tri(:,:)
      character(len=*), intent(in) :: label
      integer :: t
      real(rk) :: s
      it%name = label
      it%tri = tri
      it%slave_tri = slave_tri
      it%edges = cs%edges .and. .not. (to_lower(cs%master) == to_lower(cs%slave))
      allocate(it%apex(size(tri, 2)), source=0)
      it%slave = slave_nodes
      it%friction = cs%friction
      it%iterations = cs%iterations
      it%tracking = cs%tracking
      it%seams = cs%seams
      it%sharp_edges = cs%sharp_edges
      it%valleys = cs%valleys
      it%tolerance = cs%tolerance
      it%weights = cs%weights
      it%move_overlaps = cs%initial_overlap == overlap_move
      s = 0
      if (size(tri, 1) == 3) then
        do t = 1, size(tri, 2)
          s = s + norm2(glob%nd_x0(:,tri(2,t)) - glob%nd_x0(:,tri(1,t))) + norm2(glob%nd_x0(:,tri(3,t)) - &
              glob%nd_x0(:,tri(2,t))) + norm2(glob%nd_x0(:,tri(1,t)) - glob%nd_x0(:,tri(3,t)))
        end do
        it%h_mean = s/max(3*size(tri, 2), 1)
      else
        ! 2D: the mean segment length
        do t = 1, size(tri, 2)
          s = s + norm2(glob%nd_x0(:,tri(2,t)) - glob%nd_x0(:,tri(1,t)))
        end do
        it%h_mean = s/max(size(tri, 2), 1)
      end if
      ! half an element of reach beyond the margin: a full search every few
      ! cycles at moderate speeds, every cycle when a node moves half an
      ! element a step (3 km/s)
      if (it%tracking) it%skin = 0.5_rk*it%h_mean
      call size_interface_work(it)
    end subroutine
  end subroutine

  !> The feature edges of an interface's two surfaces, judged on the
  !> initial positions x (so a restart finds the same ones as the straight
  !> run), and their work arrays (edge-to-edge contact).
  subroutine contact_edges(it, x)
    type(interface_t), intent(inout) :: it
    real(rk), intent(in) :: x(:,:)          !< initial positions of the contact nodes
    it%edge_m = feature_edges(it%tri, x)
    it%edge_s = feature_edges(it%slave_tri, x)
    if (allocated(it%edge_lo)) deallocate(it%edge_lo, it%edge_hi)
    allocate(it%edge_lo(3, size(it%edge_m, 2)), it%edge_hi(3, size(it%edge_m, 2)))
  end subroutine

  !> The elements (tetrahedra, 2D triangles) of the parts that erode
  !> (contact-node indices, ascending global element), the neighbour across
  !> the face opposite each corner (same part), all alive.
  subroutine eroding_topology(glob, part_erodes, cn_of, ct)
    type(domain_t), intent(in) :: glob
    logical, intent(in) :: part_erodes(:)
    integer, intent(in) :: cn_of(:)
    type(contact_t), intent(inout) :: ct
    integer, allocatable :: tet_of(:), fill(:)
    integer :: e, t, f, k, e2, a, b, c, nc, fn(3)
    nc = glob%corners
    ct%tet_gidx = pack([(e, e = 1, glob%n_elems)], part_erodes(glob%el_part))
    ct%n_tets = size(ct%tet_gidx)
    allocate(tet_of(glob%n_elems), source=0)
    tet_of(ct%tet_gidx) = [(t, t = 1, ct%n_tets)]
    allocate(ct%tet(nc, ct%n_tets), ct%tet_part(ct%n_tets), ct%tet_nbr(nc, ct%n_tets), ct%tet_alive(ct%n_tets), &
             ct%alive_count(ct%n_nodes))
    ct%tet_alive = .true.
    ct%tet_nbr = 0
    do t = 1, ct%n_tets
      e = ct%tet_gidx(t)
      ct%tet(:,t) = cn_of(glob%el_conn(e,:))
      ct%tet_part(t) = glob%el_part(e)
      do f = 1, nc
        ! the face's nodes (a 2D edge: its second node twice)
        fn(1:nc-1) = element_face(nc, f)
        a = glob%el_conn(e, fn(1))
        b = glob%el_conn(e, fn(2))
        c = glob%el_conn(e, fn(nc-1))
        do k = glob%nd_el_ptr(a), glob%nd_el_ptr(a+1) - 1
          e2 = glob%nd_el(k)
          if (e2 == e .or. glob%el_part(e2) /= glob%el_part(e)) cycle
          if (any(glob%el_conn(e2,:) == b) .and. any(glob%el_conn(e2,:) == c)) then
            ct%tet_nbr(f,t) = tet_of(e2)
            exit
          end if
        end do
      end do
    end do
    ! the tetrahedra at each contact node, ascending
    allocate(ct%node_tet_ptr(ct%n_nodes+1), source=0)
    do t = 1, ct%n_tets
      ct%node_tet_ptr(ct%tet(:,t)+1) = ct%node_tet_ptr(ct%tet(:,t)+1) + 1
    end do
    ct%node_tet_ptr(1) = 1
    do k = 1, ct%n_nodes
      ct%node_tet_ptr(k+1) = ct%node_tet_ptr(k+1) + ct%node_tet_ptr(k)
    end do
    allocate(ct%node_tet(nc*ct%n_tets), fill(ct%n_nodes))
    fill = ct%node_tet_ptr(1:ct%n_nodes)
    do t = 1, ct%n_tets
      do a = 1, nc
        ct%node_tet(fill(ct%tet(a,t))) = t
        fill(ct%tet(a,t)) = fill(ct%tet(a,t)) + 1
      end do
    end do
  end subroutine

  !> Faces of each part's boundary: faces of its elements that no other
  !> element of the same part shares; counter-clockwise seen from outside
  !> (tetrahedra: triangles face(3,:); 2D triangles: edges face(2,:), in
  !> their triangle's counter-clockwise order).
  subroutine exterior_faces(glob, face, face_part, nf)
    type(domain_t), intent(in) :: glob
    integer, allocatable, intent(out) :: face(:,:), face_part(:)
    integer, intent(out) :: nf
    integer :: e, f, k, e2, j, nv, fn(3)
    logical :: shared, has_all
    nv = glob%corners - 1
    allocate(face(nv, glob%corners*glob%n_elems), face_part(glob%corners*glob%n_elems))
    nf = 0
    do e = 1, glob%n_elems
      do f = 1, glob%corners
        fn(1:nv) = glob%el_conn(e, element_face(glob%corners, f))
        shared = .false.
        do k = glob%nd_el_ptr(fn(1)), glob%nd_el_ptr(fn(1)+1) - 1
          e2 = glob%nd_el(k)
          if (e2 == e .or. glob%el_part(e2) /= glob%el_part(e)) cycle
          has_all = .true.
          do j = 2, nv
            has_all = has_all .and. any(glob%el_conn(e2,:) == fn(j))
          end do
          if (has_all) then
            shared = .true.
            exit
          end if
        end do
        if (shared) cycle
        nf = nf + 1
        face(:,nf) = fn(1:nv)
        face_part(nf) = glob%el_part(e)
      end do
    end do
  end subroutine

  !> Global node index of each mesh node (0 for nodes no tetrahedron uses),
  !> through the mesh-file tags (ascending in the mesh).
  subroutine mesh_to_global(mesh, glob, node_g)
    type(gmsh_mesh_t), intent(in) :: mesh
    type(domain_t), intent(in) :: glob
    integer, allocatable, intent(out) :: node_g(:)
    integer :: g, lo, hi, mid
    allocate(node_g(mesh%n_nodes), source=0)
    do g = 1, glob%n_nodes
      lo = 1; hi = mesh%n_nodes
      do while (lo < hi)
        mid = (lo + hi)/2
        if (mesh%node_tag(mid) < glob%nd_id(g)) then
          lo = mid + 1
        else
          hi = mid
        end if
      end do
      node_g(lo) = g
    end do
  end subroutine

  !> Each contact node's projector onto the motions its symmetry planes
  !> allow, one for every distinct set of planes (plane_proj, plane_set):
  !> the matching and the returns take it at every row (theory.md 11).
  subroutine plane_projectors(ct)
    type(contact_t), intent(inout) :: ct
    integer, allocatable :: sets(:)
    integer :: n, s
    allocate(sets(0))
    allocate(ct%plane_set(ct%n_nodes), source=0)
    do n = 1, ct%n_nodes
      if (ct%sym_planes(n) == 0) cycle
      s = findloc(sets, ct%sym_planes(n), dim=1)
      if (s == 0) then
        sets = [sets, ct%sym_planes(n)]
        s = size(sets)
      end if
      ct%plane_set(n) = s
    end do
    allocate(ct%plane_proj(3, 3, 0:size(sets)))
    ct%plane_proj(:,:,0) = constrained_projection(0, ct%plane)
    do s = 1, size(sets)
      ct%plane_proj(:,:,s) = constrained_projection(sets(s), ct%plane)
    end do
  end subroutine

  !> For every node a bit set of the symmetry planes it lies on (bit p for
  !> the p-th distinct plane: normal and offset; at most 31 planes).
  function symmetry_planes(glob, planes) result(bits)
    type(domain_t), intent(in) :: glob
    real(rk), allocatable, intent(out) :: planes(:,:)   !< (4, planes) unit normal, offset
    integer, allocatable :: bits(:)
    real(rk) :: plane(4, 31), nd(4), scale, c
    integer :: k, p, n_planes
    allocate(bits(glob%n_nodes), source=0)
    n_planes = 0
    if (.not. allocated(glob%sym_nodes)) then
      allocate(planes(4, 0))
      return
    end if
    scale = maxval(abs(glob%nd_x0))
    do k = 1, size(glob%sym_nodes)
      nd(1:3) = glob%sym_normal(k,:)
      nd(4) = dot_product(nd(1:3), glob%nd_x0(:, glob%sym_nodes(k)))
      do p = 1, n_planes
        c = dot_product(plane(1:3,p), nd(1:3))
        if (abs(c) > 1.0_rk - 1.0e-9_rk .and. abs(plane(4,p) - sign(1.0_rk, c)*nd(4)) <= 1.0e-9_rk*scale) exit
      end do
      if (p > n_planes) then
        if (n_planes == size(plane, 2)) cycle
        n_planes = n_planes + 1
        plane(:,n_planes) = nd
      end if
      bits(glob%sym_nodes(k)) = ibset(bits(glob%sym_nodes(k)), p - 1)
    end do
    planes = plane(:, 1:n_planes)
  end function

  !> The distinct nodes of a triangle list, ascending.
  function unique_nodes(tri) result(nodes)
    integer, intent(in) :: tri(:,:)
    integer, allocatable :: nodes(:)
    logical, allocatable :: mark(:)
    integer :: n
    if (size(tri) == 0) then
      allocate(nodes(0))
      return
    end if
    allocate(mark(maxval(tri)), source=.false.)
    mark(reshape(tri, [size(tri)])) = .true.
    nodes = pack([(n, n = 1, size(mark))], mark)
  end function
end module udar_contact_setup
