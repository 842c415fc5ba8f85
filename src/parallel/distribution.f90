!> From the global mesh domain (every rank reads the mesh; udar_setup builds
!> it without state) and the element partition to this rank's local domain
!> and its halo. The local domain gets the mesh domain's arrays only; the
!> caller frees the global one before udar_setup's init_state allocates the
!> state, so that the two never coexist.
!>
!> Rules (the same as udar_decomposition): an element belongs to the rank
!> METIS gives it; a node to the rank of its lowest-id incident element. A
!> rank holds its owned elements plus every element touching one of its
!> nodes (ghost elements, computed redundantly so that an owned node's force
!> is summed from all its elements in ascending global id, exactly as on
!> one rank), and every node of those elements. Local nodes: owned first,
!> then ghosts, each ascending in global id. Local elements: ascending in
!> global id, so every node->element list stays in global order.
module udar_distribution
  use udar_kinds, only: rk
  use udar_domain, only: domain_t
  use udar_setup, only: build_incidence, build_blocks, build_node_schedule
  use udar_comms, only: halo_t, halo_max_components, comms_size, comms_alltoall_counts, comms_alltoallv_int
  implicit none
  private
  public :: distribute_domain, node_owners

contains

  !> Owner rank of every global node: the rank of its lowest-id element.
  pure subroutine node_owners(glob, part, owner)
    type(domain_t), intent(in) :: glob
    integer, intent(in) :: part(:)
    integer, intent(out) :: owner(:)
    integer :: n
    do n = 1, glob%n_nodes
      owner(n) = part(glob%nd_el(glob%nd_el_ptr(n)))
    end do
  end subroutine

  !> The local domain of rank me (0-based) and its halo. Collective: the
  !> halo is agreed with the other ranks.
  subroutine distribute_domain(glob, part, me, loc, halo)
    type(domain_t), intent(in) :: glob
    integer, intent(in) :: part(:), me
    type(domain_t), intent(out) :: loc
    type(halo_t), intent(out) :: halo
    integer, allocatable :: owner(:), node_l(:), elem_l(:), ghost_owner(:)
    integer :: n, e, k, a, nl, el

    allocate(owner(glob%n_nodes), node_l(glob%n_nodes), elem_l(glob%n_elems))
    call node_owners(glob, part, owner)
    ! local elements: owned, or touching an owned node
    elem_l = 0
    do e = 1, glob%n_elems
      if (part(e) == me) elem_l(e) = 1
    end do
    do n = 1, glob%n_nodes
      if (owner(n) /= me) cycle
      do k = glob%nd_el_ptr(n), glob%nd_el_ptr(n+1) - 1
        elem_l(glob%nd_el(k)) = 1
      end do
    end do
    ! local nodes: those of local elements; owned first, then ghosts
    node_l = 0
    do e = 1, glob%n_elems
      if (elem_l(e) /= 0) node_l(glob%el_conn(e,:)) = 1
    end do
    nl = 0
    do n = 1, glob%n_nodes
      if (node_l(n) /= 0 .and. owner(n) == me) then
        nl = nl + 1; node_l(n) = nl
      end if
    end do
    loc%n_owned_nodes = nl
    do n = 1, glob%n_nodes
      if (node_l(n) /= 0 .and. owner(n) /= me) then
        nl = nl + 1; node_l(n) = nl
      end if
    end do
    el = 0
    do e = 1, glob%n_elems
      if (elem_l(e) /= 0) then
        el = el + 1; elem_l(e) = el
      end if
    end do

    loc%n_nodes = nl
    loc%n_elems = el
    loc%n_global_nodes = glob%n_nodes
    loc%n_global_elems = glob%n_elems
    allocate(loc%nd_gidx(nl), loc%el_gidx(el), ghost_owner(loc%n_owned_nodes+1:nl))
    do n = 1, glob%n_nodes
      if (node_l(n) /= 0) loc%nd_gidx(node_l(n)) = n
    end do
    do e = 1, glob%n_elems
      if (elem_l(e) /= 0) loc%el_gidx(elem_l(e)) = e
    end do
    do n = loc%n_owned_nodes + 1, nl
      ghost_owner(n) = owner(loc%nd_gidx(n))
    end do
    associate (gn => loc%nd_gidx, ge => loc%el_gidx)
      ! nodal masses and reference volumes are sums over all of a node's
      ! elements (a ghost node lacks some): taken from the whole mesh
      loc%nd_id = glob%nd_id(gn)
      loc%nd_part = glob%nd_part(gn)
      loc%nd_x0 = glob%nd_x0(:,gn)
      loc%nd_v = glob%nd_v(:,gn)
      loc%nd_mass = glob%nd_mass(gn)
      loc%nd_vol0 = glob%nd_vol0(gn)
      loc%el_id = glob%el_id(ge)
      loc%el_part = glob%el_part(ge)
      loc%el_mat = glob%el_mat(ge)
      allocate(loc%el_conn(el,glob%corners))
      loc%corners = glob%corners
      loc%corner_share = glob%corner_share
      loc%geometry = glob%geometry
      do a = 1, glob%corners
        loc%el_conn(:,a) = node_l(glob%el_conn(ge,a))
      end do
      loc%el_owned = part(ge) == me
      loc%el_owned_list = pack([(e, e = 1, el)], loc%el_owned)
      loc%el_vol0 = glob%el_vol0(ge)
    end associate
    loc%mat = glob%mat
    call build_incidence(loc)
    call build_blocks(loc)
    call build_node_schedule(loc)
    ! model and conditions (velocity conditions on every local node: harmless
    ! on ghosts, which the halo overwrites)
    loc%n_parts = glob%n_parts
    loc%part_name = glob%part_name
    loc%part_temp0 = glob%part_temp0
    loc%fixed_nodes = pack(node_l(glob%fixed_nodes), node_l(glob%fixed_nodes) /= 0)
    loc%sym_nodes = pack(node_l(glob%sym_nodes), node_l(glob%sym_nodes) /= 0)
    allocate(loc%sym_normal(size(loc%sym_nodes), 3))
    do a = 1, 3
      loc%sym_normal(:,a) = pack(glob%sym_normal(:,a), node_l(glob%sym_nodes) /= 0)
    end do
    loc%walls = glob%walls
    loc%sym_walls = glob%sym_walls
    ! gauges: the global description, and the local index of what this rank owns
    loc%gauge_name = glob%gauge_name
    loc%gauge_kind = glob%gauge_kind
    loc%gauge_nodes = glob%gauge_nodes
    loc%gauge_w = glob%gauge_w
    loc%gauge_elem = glob%gauge_elem
    allocate(loc%gauge_nodes_loc(4, size(glob%gauge_kind)), loc%gauge_elem_loc(size(glob%gauge_kind)))
    loc%gauge_nodes_loc = 0
    loc%gauge_elem_loc = 0
    do e = 1, size(glob%gauge_kind)
      do a = 1, 4
        n = glob%gauge_nodes(a,e)
        if (n > 0) then
          if (node_l(n) > 0 .and. node_l(n) <= loc%n_owned_nodes) loc%gauge_nodes_loc(a,e) = node_l(n)
        end if
      end do
      n = glob%gauge_elem(e)
      if (n > 0) then
        if (elem_l(n) > 0 .and. part(n) == me) loc%gauge_elem_loc(e) = elem_l(n)
      end if
    end do
    loc%anti_locking = glob%anti_locking
    loc%tet_formulation = glob%tet_formulation
    loc%stab_beta = glob%stab_beta
    loc%stab_beta_large = glob%stab_beta_large
    loc%stab_onset = glob%stab_onset
    loc%q_linear = glob%q_linear
    loc%q_quadratic = glob%q_quadratic

    call build_halo(loc, ghost_owner, node_l, halo)
  end subroutine

  !> Each rank asks the owners of its ghost nodes for them (global ids,
  !> ascending per owner); the owners answer with the local indices to send.
  subroutine build_halo(loc, ghost_owner, node_l, h)
    type(domain_t), intent(in) :: loc
    integer, intent(in) :: ghost_owner(loc%n_owned_nodes+1:), node_l(:)
    type(halo_t), intent(out) :: h
    integer, allocatable :: want_count(:), give_count(:), want(:), give(:), want_local(:), fill(:)
    integer :: np, q, n, k, i, nw, ng
    np = comms_size()
    allocate(want_count(0:np-1), give_count(0:np-1), fill(0:np-1))
    want_count = 0
    do n = loc%n_owned_nodes + 1, loc%n_nodes
      want_count(ghost_owner(n)) = want_count(ghost_owner(n)) + 1
    end do
    nw = sum(want_count)
    ! requests grouped by owner, ascending global id within each group
    allocate(want(max(nw,1)), want_local(max(nw,1)))
    fill(0) = 0
    do q = 1, np - 1
      fill(q) = fill(q-1) + want_count(q-1)
    end do
    do n = loc%n_owned_nodes + 1, loc%n_nodes
      q = ghost_owner(n)
      fill(q) = fill(q) + 1
      want(fill(q)) = loc%nd_gidx(n)
      want_local(fill(q)) = n
    end do
    call comms_alltoall_counts(want_count, give_count)
    ng = sum(give_count)
    allocate(give(max(ng,1)))
    call comms_alltoallv_int(want, want_count, give, give_count)

    h%n_neighbors = count(want_count > 0 .or. give_count > 0)
    allocate(h%neighbor(h%n_neighbors), h%send_ptr(h%n_neighbors+1), h%recv_ptr(h%n_neighbors+1), &
             h%send_idx(ng), h%recv_idx(nw))
    h%send_ptr(1) = 1; h%recv_ptr(1) = 1
    i = 0
    do q = 0, np - 1
      if (want_count(q) == 0 .and. give_count(q) == 0) cycle
      i = i + 1
      h%neighbor(i) = q
      h%send_ptr(i+1) = h%send_ptr(i) + give_count(q)
      h%recv_ptr(i+1) = h%recv_ptr(i) + want_count(q)
    end do
    ! both arrays are grouped by ascending rank, and so are the neighbours
    do k = 1, ng
      h%send_idx(k) = node_l(give(k))
    end do
    h%recv_idx = want_local(1:nw)
    allocate(h%send_buf(halo_max_components*ng + 1), h%recv_buf(halo_max_components*nw + 1), &
             h%requests(2*h%n_neighbors))
    if (any(h%send_idx < 1) .or. any(h%send_idx > loc%n_owned_nodes)) error stop 'udar: halo: a rank was asked '// &
      'for a node it does not own (internal error)'
  end subroutine
end module udar_distribution
