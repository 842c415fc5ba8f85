!> Builds the global mesh domain from the mesh and the deck: parts and
!> materials, lumped masses, node->element lists, velocity conditions, walls.
!> Every rank holds it at start-up, so it carries only what the partition,
!> the ownership rules, contact set-up and the mesh hash need; the element
!> and nodal state is allocated on the local domains only (init_state).
!> Mesh-dependent deck mistakes (unknown group names, a curved symmetry
!> surface) are added to the same error list as the deck's own.
module udar_setup
  use udar_kinds, only: rk, i8, max_name_len
  use udar_ordering, only: morton_keys, stable_sort_permutation
  use udar_strings, only: itoa, r2s
  use udar_config, only: config_t, bc_fixed, bc_symmetry, bc_rigid_wall, wall_frictionless, tet_plain, tet_stabilised, &
      tet_stabilised_linear, geometry_solid, geometry_axisymmetric
  use udar_gmsh, only: gmsh_mesh_t
  use udar_nodal, only: apply_velocity_conditions
  use udar_domain, only: domain_t, block_size, wall_t, gauge_node, gauge_element, gauge_point
  use udar_input_errors, only: input_errors_t
  use udar_deck, only: deck_where
  use udar_tet4, only: tet_volume
  use udar_tri_driver, only: tri_cell_volume
  use udar_strength, only: initial_hardening, thermal_softening
  implicit none
  private
  public :: build_domain, init_state, count_bodies, build_incidence, build_blocks, build_node_schedule, find_group, group_list

contains

  !> Frees the mesh's tetrahedra and coordinates once they are used (the
  !> start-up peak); its surface triangles and groups stay for the contact set-up.
  subroutine build_domain(cfg, mesh, dom, errs)
    type(config_t), intent(in) :: cfg
    type(gmsh_mesh_t), intent(inout) :: mesh
    type(domain_t), intent(out) :: dom
    type(input_errors_t), intent(inout) :: errs
    integer, allocatable :: group_part(:), node_new(:), used(:), perm(:), elem_order(:)
    integer(i8), allocatable :: keys(:)
    real(rk), allocatable :: centroid(:,:), el_mass(:)
    integer :: ip, ig, e, n, a, k, n_err0, dim, nc
    character(len=:), allocatable :: where, body_groups, cells
    real(rk) :: xe(4,3), x3(3,3)

    n_err0 = errs%count()
    dim = mesh%dim
    nc = dim + 1
    body_groups = trim(group_word(dim))//' group'
    cells = merge('4-node tetrahedra', '3-node triangles ', dim == 3)
    if (cfg%mesh%geometry == geometry_axisymmetric) then
      ! the axis is r = 0: round-off in the mesh file is no radius
      where (abs(mesh%x(:,1)) <= 1.0e-12_rk*maxval(abs(mesh%x))) mesh%x(:,1) = 0.0_rk
    end if
    if (cfg%mesh%geometry /= geometry_solid) call planar_checks(cfg, mesh, errs)
    ! parts <- physical volume groups (2D: surface groups), by name
    allocate(group_part(mesh%n_groups), source=0)
    do ip = 1, size(cfg%parts)
      ig = find_group(mesh, cfg%parts(ip)%group, dim)
      where = ''
      if (ig == 0) then
        where = deck_where(cfg, 'part', ip, 'group')      ! file:line: &part #k: group = '...'
      else if (group_part(ig) /= 0) then
        where = deck_where(cfg, 'part', ip, 'group')
      end if
      if (ig == 0) then
        call errs%add(where//": no "//body_groups//" of that name in " &
          //trim(cfg%mesh%file)//' ('//trim(group_word(dim, short=.true.))//' groups: '//group_list(mesh, dim)//')')
      else if (group_part(ig) /= 0) then
        call errs%add(where//" is already used by &part #"//itoa(group_part(ig)))
      else
        group_part(ig) = ip
        ! a part without elements is a wrong group name or a mesh saved without it
        if (.not. any(mesh%cell_group == ig)) call errs%add(deck_where(cfg, 'part', ip, 'group')// &
          ': the '//body_groups//' has no '//trim(cells)//' in '//trim(cfg%mesh%file)// &
          ' ('//trim(group_word(dim, short=.true.))//' groups: '//group_list(mesh, dim)//')')
      end if
    end do
    do ig = 1, mesh%n_groups
      if (mesh%groups(ig)%dim == dim .and. group_part(ig) == 0 .and. find_group(mesh, mesh%groups(ig)%name, dim) == ig) then
        if (any(mesh%cell_group == ig)) call errs%add(deck_where(cfg, 'mesh', 1, 'file')//": "//body_groups//" '" &
          //trim(mesh%groups(ig)%name)//"' of "//trim(cfg%mesh%file)//' has elements but no &part gives it a material')
      end if
    end do
    call boundaries_check(cfg, mesh, errs)
    if (errs%count() > n_err0) return

    ! nodes: only those used by the cells; nodes and elements stored in a
    ! space-filling-curve order (elements grouped by material) so that
    ! neighbours are near in memory. The order derives from the mesh alone,
    ! so it is the same global numbering on every rank; the mesh-file tags
    ! are kept as the ids.
    allocate(node_new(mesh%n_nodes), source=0)
    do a = 1, nc
      node_new(mesh%cell(:,a)) = 1
    end do
    used = pack([(n, n = 1, mesh%n_nodes)], node_new /= 0)
    dom%n_nodes = size(used)
    dom%n_elems = mesh%n_cells
    allocate(keys(dom%n_nodes), perm(dom%n_nodes))
    call morton_keys(mesh%x(used,:), keys)
    call stable_sort_permutation(keys, perm)
    node_new(used(perm)) = [(n, n = 1, dom%n_nodes)]
    allocate(dom%nd_id(dom%n_nodes), dom%nd_part(dom%n_nodes), dom%nd_x0(3,dom%n_nodes), dom%nd_v(3,dom%n_nodes), &
             dom%nd_mass(dom%n_nodes), dom%nd_vol0(dom%n_nodes))
    allocate(dom%el_id(dom%n_elems), dom%el_part(dom%n_elems), dom%el_mat(dom%n_elems), dom%el_conn(dom%n_elems,nc), &
             dom%el_vol0(dom%n_elems))
    dom%nd_id = mesh%node_tag(used(perm))
    dom%nd_x0 = transpose(mesh%x(used(perm),:))
    deallocate(keys, perm)
    allocate(keys(dom%n_elems), perm(dom%n_elems), centroid(dom%n_elems,3), elem_order(dom%n_elems))
    do k = 1, 3
      centroid(:,k) = mesh%x(mesh%cell(:,1),k)
      do a = 2, nc
        centroid(:,k) = centroid(:,k) + mesh%x(mesh%cell(:,a),k)
      end do
      centroid(:,k) = centroid(:,k)/nc
    end do
    call morton_keys(centroid, keys)
    deallocate(centroid)
    call stable_sort_permutation(keys, perm)
    ! then by material, keeping the curve order inside each material
    do e = 1, dom%n_elems
      keys(e) = int(material_index(cfg, cfg%parts(group_part(mesh%cell_group(perm(e))))%material), i8)
    end do
    call stable_sort_permutation(keys, elem_order)
    elem_order = perm(elem_order)
    deallocate(keys, perm)
    dom%el_id = mesh%cell_tag(elem_order)
    do a = 1, nc
      dom%el_conn(:,a) = node_new(mesh%cell(elem_order,a))
    end do
    dom%corners = nc
    dom%corner_share = 1.0_rk/nc
    dom%geometry = cfg%mesh%geometry
    deallocate(mesh%cell, mesh%cell_tag)

    call resolve_gauges(cfg, dom, errs)
    if (errs%count() > n_err0) return

    ! materials and parts
    dom%mat = cfg%materials
    dom%n_parts = size(cfg%parts)
    allocate(dom%part_name(dom%n_parts), dom%part_temp0(dom%n_parts))
    do ip = 1, dom%n_parts
      dom%part_name(ip) = cfg%parts(ip)%group
      ! its own initial temperature, or its material's
      dom%part_temp0(ip) = cfg%parts(ip)%initial_temperature
      if (dom%part_temp0(ip) <= 0.0_rk) &
        dom%part_temp0(ip) = cfg%materials(material_index(cfg, cfg%parts(ip)%material))%initial_temperature
    end do
    allocate(el_mass(dom%n_elems))
    do e = 1, dom%n_elems
      dom%el_part(e) = group_part(mesh%cell_group(elem_order(e)))
      dom%el_mat(e) = material_index(cfg, cfg%parts(dom%el_part(e))%material)
      do a = 1, nc
        xe(a,:) = dom%nd_x0(:,dom%el_conn(e,a))
      end do
      if (nc == 4) then
        dom%el_vol0(e) = tet_volume(xe)
      else
        x3 = transpose(xe(1:3,:))
        dom%el_vol0(e) = tri_cell_volume(dom%geometry, x3)
      end if
      el_mass(e) = dom%mat(dom%el_mat(e))%rho0*dom%el_vol0(e)   ! as init_state computes it
    end do
    deallocate(mesh%cell_group, elem_order)

    ! (the corners are for the local domains' assembly only)
    call build_incidence(dom, corners=.false.)
    ! lumped masses, nodal reference volumes, node parts, initial velocities:
    ! sums over all of a node's elements, so taken here, on the whole mesh
    do n = 1, dom%n_nodes
      dom%nd_mass(n) = 0.0_rk
      dom%nd_vol0(n) = 0.0_rk
      do k = dom%nd_el_ptr(n), dom%nd_el_ptr(n+1) - 1
        dom%nd_mass(n) = dom%nd_mass(n) + dom%corner_share*el_mass(dom%nd_el(k))
        dom%nd_vol0(n) = dom%nd_vol0(n) + dom%corner_share*dom%el_vol0(dom%nd_el(k))
      end do
      dom%nd_part(n) = dom%el_part(dom%nd_el(dom%nd_el_ptr(n)))
      dom%nd_v(:,n) = cfg%parts(dom%nd_part(n))%velocity
    end do
    deallocate(el_mass)
    call build_conditions(cfg, mesh, node_new, dom)
    deallocate(mesh%x)
    ! initial velocities obey the velocity conditions (a fixed node starts at
    ! rest), so the initial energy holds no kinetic energy the first step removes
    call apply_velocity_conditions(dom)
    dom%tet_formulation = cfg%numerics%tet_formulation
    if (.not. cfg%numerics%anti_locking) dom%tet_formulation = tet_plain
    dom%anti_locking = dom%tet_formulation /= tet_plain
    ! the element's own share: growing with its departure from its nodes
    ! (geometric blend), constant at the large share (linear blend), none
    ! (plain, nodal)
    dom%stab_beta = 0.0_rk
    dom%stab_beta_large = 0.0_rk
    dom%stab_onset = cfg%numerics%stabilisation_onset
    if (dom%tet_formulation == tet_stabilised) then
      dom%stab_beta = cfg%numerics%stabilisation
      dom%stab_beta_large = cfg%numerics%stabilisation_large
    else if (dom%tet_formulation == tet_stabilised_linear) then
      dom%stab_beta = cfg%numerics%stabilisation_large
      dom%stab_beta_large = cfg%numerics%stabilisation_large
    end if
    dom%q_linear = cfg%numerics%q_linear
    dom%q_quadratic = cfg%numerics%q_quadratic
    ! the whole mesh (no local numbering, no state): udar_distribution cuts it up
    dom%n_global_nodes = dom%n_nodes
    dom%n_global_elems = dom%n_elems
    dom%n_owned_nodes = dom%n_nodes
  end subroutine

  !> The initial state of a local domain that holds the mesh domain's
  !> arrays (node ids, parts, x0, v, masses, reference volumes; element ids,
  !> parts, materials, connectivity, el_vol0): allocates and fills the rest.
  subroutine init_state(dom)
    type(domain_t), intent(inout) :: dom
    integer :: nn, ne, e
    nn = dom%n_nodes; ne = dom%n_elems
    allocate(dom%nd_x(3,nn), dom%nd_f(3,nn), dom%nd_vref(nn), dom%nd_j(nn), dom%nd_p(nn), dom%nd_k(nn))
    dom%nd_x = dom%nd_x0
    dom%nd_f = 0.0_rk; dom%nd_p = 0.0_rk; dom%nd_k = 0.0_rk
    dom%nd_vref = dom%nd_vol0
    dom%nd_j = 1.0_rk
    allocate(dom%el_vol(ne), dom%el_h(ne), dom%el_k(ne), dom%el_mass(ne), dom%el_j(ne), dom%el_e(ne), dom%el_wp(ne), dom%el_p(ne), &
             dom%el_q(ne), dom%el_pavg(ne), dom%el_s(ne,6), dom%el_eps_p(ne), dom%el_temp(ne), dom%el_hard(ne), &
             dom%el_soft(ne))
    do e = 1, ne
      dom%el_mass(e) = dom%mat(dom%el_mat(e))%rho0*dom%el_vol0(e)
      dom%el_temp(e) = dom%part_temp0(dom%el_part(e))
      dom%el_hard(e) = initial_hardening(dom%mat(dom%el_mat(e)))
      dom%el_soft(e) = thermal_softening(dom%mat(dom%el_mat(e)), dom%el_temp(e))
    end do
    dom%el_vol = dom%el_vol0
    dom%el_h = huge(1.0_rk)
    dom%el_j = 1.0_rk
    dom%el_e = 0.0_rk; dom%el_wp = 0.0_rk; dom%el_p = 0.0_rk; dom%el_q = 0.0_rk; dom%el_pavg = 0.0_rk; dom%el_s = 0.0_rk
    dom%el_eps_p = 0.0_rk; dom%el_k = 0.0_rk
    allocate(dom%el_state(ne), source=0)
    allocate(dom%el_damage(ne), dom%el_eps_tot(ne), source=0.0_rk)
  end subroutine

  !> Node -> element lists by counting sort; elements are visited in
  !> ascending id, so each node's list is ascending: the assembly order.
  !> corners = .false.: without each entry's corner number (nd_el_corner).
  subroutine build_incidence(dom, corners)
    type(domain_t), intent(inout) :: dom
    logical, intent(in), optional :: corners
    integer, allocatable :: fill(:)
    integer :: e, a, n, k
    logical :: with_corners
    with_corners = .true.
    if (present(corners)) with_corners = corners
    allocate(dom%nd_el_ptr(dom%n_nodes+1), source=0)
    do a = 1, dom%corners
      do e = 1, dom%n_elems
        n = dom%el_conn(e,a)
        dom%nd_el_ptr(n+1) = dom%nd_el_ptr(n+1) + 1
      end do
    end do
    dom%nd_el_ptr(1) = 1
    do n = 1, dom%n_nodes
      dom%nd_el_ptr(n+1) = dom%nd_el_ptr(n+1) + dom%nd_el_ptr(n)
    end do
    allocate(dom%nd_el(dom%nd_el_ptr(dom%n_nodes+1)-1))
    if (with_corners) allocate(dom%nd_el_corner(dom%nd_el_ptr(dom%n_nodes+1)-1))
    allocate(fill(dom%n_nodes), source=dom%nd_el_ptr(1:dom%n_nodes))
    do e = 1, dom%n_elems
      do a = 1, dom%corners
        n = dom%el_conn(e,a)
        k = fill(n)
        dom%nd_el(k) = e
        if (with_corners) dom%nd_el_corner(k) = a
        fill(n) = k + 1
      end do
    end do
  end subroutine

  !> Blocks of at most block_size consecutive elements of one material.
  subroutine build_blocks(dom)
    type(domain_t), intent(inout) :: dom
    integer :: e, nb, first
    integer, allocatable :: f(:), l(:)
    allocate(f(dom%n_elems), l(dom%n_elems))
    nb = 0; first = 1
    do e = 1, dom%n_elems
      if (e == dom%n_elems) then
        nb = nb + 1; f(nb) = first; l(nb) = e
      else if (dom%el_mat(e+1) /= dom%el_mat(first) .or. e - first + 1 == block_size) then
        nb = nb + 1; f(nb) = first; l(nb) = e
        first = e + 1
      end if
    end do
    dom%n_blocks = nb
    dom%blk_first = f(1:nb)
    dom%blk_last = l(1:nb)
    allocate(dom%blk_ticks(nb), source=0_i8)
  end subroutine

  !> The owned nodes grouped by the block of their last incident element
  !> (domain_t blk_nd), ascending within a block (counting sort); a node
  !> without elements goes with block 1. Needs the incidence, the blocks
  !> and n_owned_nodes.
  subroutine build_node_schedule(dom)
    type(domain_t), intent(inout) :: dom
    integer, allocatable :: blk_of(:), nd_blk(:), fill(:)
    integer :: b, n, k
    allocate(blk_of(dom%n_elems), nd_blk(dom%n_owned_nodes))
    do b = 1, dom%n_blocks
      blk_of(dom%blk_first(b):dom%blk_last(b)) = b
    end do
    if (allocated(dom%blk_nd_ptr)) deallocate(dom%blk_nd_ptr, dom%blk_nd)
    allocate(dom%blk_nd_ptr(max(dom%n_blocks, 1) + 1), source=0)
    do n = 1, dom%n_owned_nodes
      nd_blk(n) = 1
      if (dom%nd_el_ptr(n+1) > dom%nd_el_ptr(n)) nd_blk(n) = blk_of(dom%nd_el(dom%nd_el_ptr(n+1) - 1))
      dom%blk_nd_ptr(nd_blk(n)+1) = dom%blk_nd_ptr(nd_blk(n)+1) + 1
    end do
    dom%blk_nd_ptr(1) = 1
    do b = 1, size(dom%blk_nd_ptr) - 1
      dom%blk_nd_ptr(b+1) = dom%blk_nd_ptr(b+1) + dom%blk_nd_ptr(b)
    end do
    allocate(dom%blk_nd(dom%n_owned_nodes))
    allocate(fill(size(dom%blk_nd_ptr) - 1), source=dom%blk_nd_ptr(1:size(dom%blk_nd_ptr)-1))
    do n = 1, dom%n_owned_nodes
      k = fill(nd_blk(n))
      dom%blk_nd(k) = n
      fill(nd_blk(n)) = k + 1
    end do
  end subroutine

  !> Each &gauge's node, element or material point on the whole mesh: its
  !> global node and element indices and, for a point, the element that
  !> holds it (the lowest in the global order where it lies on a face
  !> shared by several) and its barycentric weights there.
  subroutine resolve_gauges(cfg, dom, errs)
    type(config_t), intent(in) :: cfg
    type(domain_t), intent(inout) :: dom
    type(input_errors_t), intent(inout) :: errs
    integer :: ng, g, e, nc
    real(rk) :: w(4), best
    ng = 0
    if (allocated(cfg%gauges)) ng = size(cfg%gauges)
    nc = dom%corners
    allocate(dom%gauge_name(ng), dom%gauge_kind(ng), dom%gauge_nodes(4,ng), dom%gauge_w(4,ng), dom%gauge_elem(ng))
    dom%gauge_nodes = 0
    dom%gauge_w = 0.0_rk
    dom%gauge_elem = 0
    do g = 1, ng
      associate (gc => cfg%gauges(g))
        dom%gauge_name(g) = gc%name
        if (gc%node > 0) then
          dom%gauge_kind(g) = gauge_node
          dom%gauge_nodes(1,g) = findloc(dom%nd_id, gc%node, 1)
          dom%gauge_w(1,g) = 1.0_rk
          if (dom%gauge_nodes(1,g) == 0) call errs%add(deck_where(cfg, 'gauge', g, 'node')// &
            ': no node of that tag in the elements of '//trim(cfg%mesh%file))
        else if (gc%element > 0) then
          dom%gauge_kind(g) = gauge_element
          dom%gauge_elem(g) = findloc(dom%el_id, gc%element, 1)
          if (dom%gauge_elem(g) == 0) call errs%add(deck_where(cfg, 'gauge', g, 'element')// &
            ': no '//trim(merge('tetrahedron', 'triangle   ', nc == 4))//' of that tag in '//trim(cfg%mesh%file))
        else
          dom%gauge_kind(g) = gauge_point
          ! the first element in the global order that holds it (weights
          ! >= 0 but for round-off)
          best = -huge(1.0_rk)
          do e = 1, dom%n_elems
            w = barycentric(dom, e, gc%point*[1.0_rk, 1.0_rk, merge(1.0_rk, 0.0_rk, nc == 4)])
            if (minval(w(1:nc)) >= -1.0e-9_rk) then
              best = minval(w(1:nc))
              dom%gauge_elem(g) = e
              dom%gauge_w(:,g) = w
              exit
            end if
          end do
          if (best < -1.0e-9_rk) then
            call errs%add(deck_where(cfg, 'gauge', g, 'point')//': the point is in no element of '// &
              trim(cfg%mesh%file)//' (the deck gives it in m, the mesh is scaled by &mesh scale)')
          else
            dom%gauge_nodes(1:nc,g) = dom%el_conn(dom%gauge_elem(g),:)
          end if
        end if
      end associate
    end do
  end subroutine

  !> The barycentric weights of point x in element e of the undeformed
  !> mesh (a triangle: the first three, z ignored).
  function barycentric(dom, e, x) result(w)
    type(domain_t), intent(in) :: dom
    integer, intent(in) :: e
    real(rk), intent(in) :: x(3)
    real(rk) :: w(4), a(3,3), r(3), det
    integer :: k
    w = 0.0_rk
    if (dom%corners == 4) then
      do k = 1, 3
        a(:,k) = dom%nd_x0(:,dom%el_conn(e,k+1)) - dom%nd_x0(:,dom%el_conn(e,1))
      end do
      r = x - dom%nd_x0(:,dom%el_conn(e,1))
      det = dot_product(a(:,1), cross3(a(:,2), a(:,3)))
      if (det == 0.0_rk) then
        w = -huge(1.0_rk)
        return
      end if
      ! Cramer: w(2:4) solve a w = r
      w(2) = dot_product(r, cross3(a(:,2), a(:,3)))/det
      w(3) = dot_product(a(:,1), cross3(r, a(:,3)))/det
      w(4) = dot_product(a(:,1), cross3(a(:,2), r))/det
      w(1) = 1.0_rk - w(2) - w(3) - w(4)
    else
      a(1:2,1) = dom%nd_x0(1:2,dom%el_conn(e,2)) - dom%nd_x0(1:2,dom%el_conn(e,1))
      a(1:2,2) = dom%nd_x0(1:2,dom%el_conn(e,3)) - dom%nd_x0(1:2,dom%el_conn(e,1))
      r(1:2) = x(1:2) - dom%nd_x0(1:2,dom%el_conn(e,1))
      det = a(1,1)*a(2,2) - a(2,1)*a(1,2)
      if (det == 0.0_rk) then
        w = -huge(1.0_rk)
        return
      end if
      w(2) = (r(1)*a(2,2) - r(2)*a(1,2))/det
      w(3) = (a(1,1)*r(2) - a(2,1)*r(1))/det
      w(1) = 1.0_rk - w(2) - w(3)
    end if
  contains
    pure function cross3(u, v) result(c)
      real(rk), intent(in) :: u(3), v(3)
      real(rk) :: c(3)
      c = [u(2)*v(3) - u(3)*v(2), u(3)*v(1) - u(1)*v(3), u(1)*v(2) - u(2)*v(1)]
    end function
  end function

  subroutine boundaries_check(cfg, mesh, errs)
    type(config_t), intent(in) :: cfg
    type(gmsh_mesh_t), intent(in) :: mesh
    type(input_errors_t), intent(inout) :: errs
    integer :: ib, ig
    real(rk) :: normal(3), dev
    if (.not. allocated(cfg%boundaries)) return
    do ib = 1, size(cfg%boundaries)
      if (cfg%boundaries(ib)%kind == bc_rigid_wall) cycle
      ig = find_group(mesh, cfg%boundaries(ib)%surface, mesh%dim - 1)
      if (ig == 0) then
        ! file:line: &boundary #k: surface = '...'
        call errs%add(deck_where(cfg, 'boundary', ib, 'surface')// &
          ": no "//trim(group_word(mesh%dim - 1))//" group of that name in "//trim(cfg%mesh%file)// &
          ' ('//trim(group_word(mesh%dim - 1, short=.true.))//' groups: '//group_list(mesh, mesh%dim - 1)//')')
      else if (cfg%boundaries(ib)%kind == bc_symmetry) then
        call plane_of_group(mesh, ig, normal, dev)
        if (dev > 1.0e-6_rk) call errs%add(deck_where(cfg, 'boundary', ib, 'surface')// &
          " is not "//trim(merge('planar  ', 'straight', mesh%dim == 3))//" (relative deviation "//r2s(dev)// &
          '): a symmetry '//trim(merge('surface must be a plane', 'curve must be a line   ', mesh%dim == 3)))
      end if
    end do
  end subroutine

  subroutine build_conditions(cfg, mesh, node_new, dom)
    type(config_t), intent(in) :: cfg
    type(gmsh_mesh_t), intent(in) :: mesh
    integer, intent(in) :: node_new(:)
    type(domain_t), intent(inout) :: dom
    integer :: ib, ig, n_walls, iw, n
    integer, allocatable :: nodes(:), sym(:), fix(:)
    real(rk), allocatable :: symn(:,:)
    real(rk) :: normal(3), dev, point(3)
    allocate(sym(0), fix(0), symn(0,3))
    allocate(dom%sym_walls(0))
    n_walls = 0
    if (allocated(cfg%boundaries)) n_walls = count(cfg%boundaries%kind == bc_rigid_wall)
    allocate(dom%walls(n_walls))
    iw = 0
    if (allocated(cfg%boundaries)) then
      do ib = 1, size(cfg%boundaries)
        select case (cfg%boundaries(ib)%kind)
        case (bc_rigid_wall)
          iw = iw + 1
          dom%walls(iw)%point = cfg%boundaries(ib)%point
          dom%walls(iw)%normal = cfg%boundaries(ib)%normal/norm2(cfg%boundaries(ib)%normal)
          dom%walls(iw)%wall_type = cfg%boundaries(ib)%wall_type
          dom%walls(iw)%friction = cfg%boundaries(ib)%friction
        case (bc_fixed)
          ig = find_group(mesh, cfg%boundaries(ib)%surface, mesh%dim - 1)
          call group_nodes(mesh, ig, node_new, nodes)
          fix = [fix, nodes]
        case (bc_symmetry)
          ig = find_group(mesh, cfg%boundaries(ib)%surface, mesh%dim - 1)
          call group_nodes(mesh, ig, node_new, nodes)
          call plane_of_group(mesh, ig, normal, dev, point)
          sym = [sym, nodes]
          symn = append_rows(symn, normal, size(nodes))
          ! the plane as a frictionless wall facing the body, for what is no
          ! mesh node (particles): the body is on the side of its nodes
          if (sum(matmul(mesh%x(:,1:3) - spread(point, 1, size(mesh%x, 1)), normal)) < 0.0_rk) normal = -normal
          dom%sym_walls = [dom%sym_walls, wall_t(point=point, normal=normal, wall_type=wall_frictionless)]
        end select
      end do
    end if
    if (cfg%mesh%geometry == geometry_axisymmetric) then
      ! the axis: no radial motion of the nodes on r = 0
      nodes = pack([(n, n = 1, size(node_new))], node_new /= 0 .and. mesh%x(:,1) == 0.0_rk)
      nodes = node_new(nodes)
      sym = [sym, nodes]
      symn = append_rows(symn, [1.0_rk, 0.0_rk, 0.0_rk], size(nodes))
      ! and for the particles the last of the planes (their images across
      ! it, no particle beyond it)
      dom%sym_walls = [dom%sym_walls, wall_t(point=[0.0_rk, 0.0_rk, 0.0_rk], normal=[1.0_rk, 0.0_rk, 0.0_rk], &
                                             wall_type=wall_frictionless)]
    end if
    dom%sym_nodes = sym
    dom%sym_normal = symn
    dom%fixed_nodes = fix
  end subroutine

  !> Nodes (new numbering, ascending, unique) of a boundary group's facets
  !> (surface triangles; 2D: curve segments).
  subroutine group_nodes(mesh, ig, node_new, nodes)
    type(gmsh_mesh_t), intent(in) :: mesh
    integer, intent(in) :: ig, node_new(:)
    integer, allocatable, intent(out) :: nodes(:)
    logical, allocatable :: mark(:)
    integer :: t, a
    allocate(mark(mesh%n_nodes), source=.false.)
    do t = 1, mesh%n_facets
      if (mesh%facet_group(t) /= ig) cycle
      do a = 1, mesh%dim
        mark(mesh%facet(t,a)) = .true.
      end do
    end do
    ! a boundary node that no cell uses has no mass: drop it
    where (node_new == 0) mark = .false.
    nodes = pack(node_new, mark)
  end subroutine

  !> Area-weighted unit normal of a surface group (2D: length-weighted, of a
  !> curve group, in the plane z = 0) and the largest distance of its nodes
  !> from the mean plane (line) relative to the group's extent.
  subroutine plane_of_group(mesh, ig, normal, dev, point)
    type(gmsh_mesh_t), intent(in) :: mesh
    integer, intent(in) :: ig
    real(rk), intent(out) :: normal(3), dev
    real(rk), intent(out), optional :: point(3)   !< the group's mean corner (on the plane)
    real(rk) :: c(3), a(3), b(3), x0(3), ext, lo(3), hi(3)
    integer :: t, k, cnt
    normal = 0.0_rk; x0 = 0.0_rk; cnt = 0
    lo = huge(1.0_rk); hi = -huge(1.0_rk)
    do t = 1, mesh%n_facets
      if (mesh%facet_group(t) /= ig) cycle
      a = mesh%x(mesh%facet(t,2),:) - mesh%x(mesh%facet(t,1),:)
      b = [0.0_rk, 0.0_rk, 1.0_rk]
      if (mesh%dim == 3) b = mesh%x(mesh%facet(t,3),:) - mesh%x(mesh%facet(t,1),:)
      c = [a(2)*b(3) - a(3)*b(2), a(3)*b(1) - a(1)*b(3), a(1)*b(2) - a(2)*b(1)]
      ! orient consistently with the first triangle before summing
      if (dot_product(c, normal) < 0.0_rk) c = -c
      normal = normal + c
      do k = 1, mesh%dim
        x0 = x0 + mesh%x(mesh%facet(t,k),:)
        lo = min(lo, mesh%x(mesh%facet(t,k),:)); hi = max(hi, mesh%x(mesh%facet(t,k),:))
      end do
      cnt = cnt + mesh%dim
    end do
    dev = 0.0_rk
    if (cnt == 0 .or. norm2(normal) == 0.0_rk) then
      normal = [0.0_rk, 0.0_rk, 1.0_rk]; dev = huge(1.0_rk)
      if (present(point)) point = 0.0_rk
      return
    end if
    normal = normal/norm2(normal)
    x0 = x0/cnt
    if (present(point)) point = x0
    ext = max(norm2(hi - lo), tiny(1.0_rk))
    do t = 1, mesh%n_facets
      if (mesh%facet_group(t) /= ig) cycle
      do k = 1, mesh%dim
        dev = max(dev, abs(dot_product(mesh%x(mesh%facet(t,k),:) - x0, normal))/ext)
      end do
    end do
  end subroutine

  !> Number of separate bodies: connected components of the mesh, two
  !> elements being connected when they share a node (union-find).
  integer function count_bodies(dom) result(n_bodies)
    type(domain_t), intent(in) :: dom
    integer, allocatable :: parent(:)
    integer :: e, a, r1, r2, n
    allocate(parent(dom%n_nodes))
    parent = [(n, n = 1, dom%n_nodes)]
    do e = 1, dom%n_elems
      r1 = root(dom%el_conn(e,1))
      do a = 2, dom%corners
        r2 = root(dom%el_conn(e,a))
        if (r2 /= r1) parent(r2) = r1
      end do
    end do
    n_bodies = 0
    do n = 1, dom%n_nodes
      if (root(n) == n) n_bodies = n_bodies + 1
    end do
  contains
    integer function root(i)
      integer, intent(in) :: i
      root = i
      do while (parent(root) /= root)
        parent(root) = parent(parent(root))   ! path halving
        root = parent(root)
      end do
    end function
  end function

  !> rows of a (n,3) table with n_new copies of row r appended
  function append_rows(table, r, n_new) result(out)
    real(rk), intent(in) :: table(:,:), r(3)
    integer, intent(in) :: n_new
    real(rk), allocatable :: out(:,:)
    integer :: k
    allocate(out(size(table,1) + n_new, 3))
    out(1:size(table,1),:) = table
    do k = 1, n_new
      out(size(table,1) + k,:) = r
    end do
  end function

  !> What gmsh calls a physical group of dimension dim ('physical volume',
  !> 'physical surface', 'physical curve'; short: 'volume', ...).
  function group_word(dim, short) result(w)
    integer, intent(in) :: dim
    logical, intent(in), optional :: short
    character(len=16) :: w
    character(len=7), parameter :: words(3) = [character(len=7) :: 'curve', 'surface', 'volume']
    w = 'physical '//words(max(1, min(3, dim)))
    if (present(short)) then
      if (short) w = words(max(1, min(3, dim)))
    end if
  end function

  !> A 2D deck's own rules (&mesh geometry axisymmetric or plane_strain):
  !> a 2D mesh, the deck's vectors in the plane z = 0, no node at r < 0
  !> (axisymmetric), no edge-to-edge contact.
  subroutine planar_checks(cfg, mesh, errs)
    type(config_t), intent(in) :: cfg
    type(gmsh_mesh_t), intent(in) :: mesh
    type(input_errors_t), intent(inout) :: errs
    integer :: k, n
    character(len=:), allocatable :: mode
    mode = trim(merge('axisymmetric', 'plane_strain', cfg%mesh%geometry == geometry_axisymmetric))
    do k = 1, size(cfg%parts)
      if (cfg%parts(k)%velocity(3) /= 0.0_rk) call errs%add(deck_where(cfg, 'part', k, 'velocity')// &
        ': the third component must be 0 in a 2D ('//mode//') calculation: give the velocity in the '// &
        'mesh plane, e.g. velocity = 0.0, -190.0')
    end do
    if (allocated(cfg%boundaries)) then
      do k = 1, size(cfg%boundaries)
        if (cfg%boundaries(k)%kind /= bc_rigid_wall) cycle
        if (cfg%boundaries(k)%point(3) /= 0.0_rk .or. cfg%boundaries(k)%normal(3) /= 0.0_rk) &
          call errs%add(deck_where(cfg, 'boundary', k, 'normal')//': a rigid wall is a line in the mesh plane '// &
          'in a 2D ('//mode//') calculation: point and normal with third components 0')
      end do
    end if
    if (allocated(cfg%contacts)) then
      do k = 1, size(cfg%contacts)
        if (cfg%contacts(k)%edges) call errs%add(deck_where(cfg, 'contact', k, 'edges')// &
          ': edge-to-edge contact has no 2D meaning ('//mode//'): a 2D surface''s corners are its nodes, '// &
          'which the node-to-segment contact already takes; leave it out')
      end do
    end if
    if (cfg%mesh%geometry /= geometry_axisymmetric) return
    n = findloc(mesh%x(:,1) < 0.0_rk, .true., 1)
    if (n > 0) call errs%add(deck_where(cfg, 'mesh', 1, 'file')//': node '//itoa(mesh%node_tag(n))// &
      ' is at x = '//r2s(mesh%x(n,1))//' m: an axisymmetric mesh lies in x = r >= 0 with the axis on x = 0 '// &
      '(y along the axis)')
  end subroutine

  integer function find_group(mesh, name, dim) result(ig)
    type(gmsh_mesh_t), intent(in) :: mesh
    character(len=*), intent(in) :: name
    integer, intent(in) :: dim
    do ig = 1, mesh%n_groups
      if (mesh%groups(ig)%dim == dim .and. trim(mesh%groups(ig)%name) == trim(name)) return
    end do
    ig = 0
  end function

  function group_list(mesh, dim) result(s)
    type(gmsh_mesh_t), intent(in) :: mesh
    integer, intent(in) :: dim
    character(len=:), allocatable :: s
    integer :: ig
    s = ''
    do ig = 1, mesh%n_groups
      if (mesh%groups(ig)%dim /= dim) cycle
      if (len(s) > 0) s = s//', '
      s = s//"'"//trim(mesh%groups(ig)%name)//"'"
    end do
    if (len(s) == 0) s = 'none'
  end function

  integer function material_index(cfg, name) result(im)
    type(config_t), intent(in) :: cfg
    character(len=*), intent(in) :: name
    do im = 1, size(cfg%materials)
      if (trim(cfg%materials(im)%name) == trim(name)) return
    end do
    im = 0
  end function

end module udar_setup
