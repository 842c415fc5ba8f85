!> Contact interfaces as the time loop uses them. Every rank holds the same
!> global surfaces (topology); each cycle it has the current state only of
!> the contact nodes near its share of the slave nodes (fresh) and of the
!> nodes found in contact, which every rank matches in the same order (the
!> results cannot depend on the partition); each then keeps what concerns
!> its own nodes.
module udar_contact_model
  use udar_kinds, only: rk, i8, max_name_len
  use udar_contact_search, only: bucket_grid_t
  use udar_ordering, only: stable_sort_permutation, morton_keys
  use udar_vectors, only: cross
  use udar_contact_faces, only: face_projection
  use udar_config, only: contact_weights_area
  implicit none
  private
  public :: contact_grow_nodes, size_interface_work, on_symmetry_plane, any_eroding, self_neighbourhoods, feature_edges, assign_slaves, mark_returns, &
            surface_neighbours, neighbour_across

  !> A set of rows joined by shared nodes in a joint pass (symmetric pair,
  !> self-contact) with at most joint_solve_rows rows has its rows solved
  !> together before the sweeps, normals and (every few sweeps) friction;
  !> without friction a set of up to joint_dense_rows
  integer, parameter, public :: joint_solve_rows = 64, joint_dense_rows = 512

  !> One direction of an interface: slave nodes against master triangles.
  type, public :: interface_t
    character(len=2*max_name_len+8) :: name = ''  !< 'slave_on_master', for the log and the history
    integer, allocatable :: tri(:,:)       !< (3, n_tri) contact-node indices; counter-clockwise seen from outside
    !> (n_tri) the fourth corner of each triangle's tetrahedron (eroding
    !> master parts; 0 for a fixed surface): a slave node inside that
    !> element is found however deep (exposed by erosion under it)
    integer, allocatable :: apex(:)
    !> (3 or 2, n_tri) the face across each edge of a master face (seams and
    !> sharp edges: whether a node beyond an edge is behind the surface
    !> depends on the face across it, neighbour_across)
    integer, allocatable :: across(:,:)
    integer, allocatable :: slave(:)       !< contact-node indices, ascending (= ascending global id)
    integer :: master_part = 0, slave_part = 0   !< eroding parts whose current boundary is the surface (0: fixed surface)
    !> self-contact: master and slave are one part's boundary (without its
    !> faces on symmetry planes); a node meets only triangles with no node
    !> within two surface edges of it, and only when it crossed them in
    !> this step
    logical :: self = .false.
    !> a symmetric contact's other direction (0: none): both directions'
    !> slave nodes are found first and matched in one set of passes
    integer :: partner = 0
    !> the slave nodes are only the particles of the part (its failed
    !> material, eroded = 'particles'), kept out of its own remaining body
    logical :: own_particles = .false.
    integer, allocatable :: ring_start(:), ring(:)   !< CSR over slave nodes: the nodes within two surface edges
    logical, allocatable :: near(:)        !< (contact nodes) work: the current slave node's ring
    logical, allocatable :: touched(:)     !< (slave nodes) in contact in the last pass (self-contact)
    logical, allocatable :: mine(:)        !< (slave nodes) this rank searches for it (assign_slaves)
    logical, allocatable :: exited(:)      !< (slave nodes) work array of the exit step: tested this pass
    integer, allocatable :: searcher(:)    !< (slave nodes) the rank that searches for it
    ! triangles whose nodes (and apex) are all on this rank: their size at
    ! the start of the step bounds how far a triangle reaches (rebuilt with
    ! the surfaces)
    logical :: local_tri_valid = .false.
    integer, allocatable :: local_tri(:)
    real(rk) :: friction = 0
    integer :: iterations = 50, weights = contact_weights_area
    !> nodes in the seams of a dented master surface are found (face_behind_surface;
    !> needs the node-triangle lists of surface_neighbours)
    logical :: seams = .true.
    !> a node in front of the face beside a sharp convex edge is not behind
    !> the other face (face_beside_sharp_edge; the same lists)
    logical :: sharp_edges = .true.
    !> a slave node in a valley of the master surface is matched to both
    !> faces (detect's valley_partner; up to two rows a node in the matching)
    logical :: valleys = .false.
    real(rk) :: tolerance = 0
    logical :: move_overlaps = .false.     !< initial overlaps: move the slave nodes (else report only)
    !> (slave nodes) the node starts inside a tetrahedron of the master
    !> body: only these can be initial overlaps (freed after that pass)
    logical, allocatable :: start_inside(:)
    !> (parts) whose elements are the master body (not for self-contact):
    !> a particle made inside one of its elements is put on the surface
    logical, allocatable :: master_body(:)
    real(rk) :: h_mean = 0                 !< m, mean master edge length
    type(bucket_grid_t) :: grid
    ! local tracking: each slave node's candidate triangles, found by a full
    ! (grid) search and kept while no node can have moved far enough to
    ! meet a triangle outside its list
    logical :: tracking = .true.
    real(rk) :: skin = 0                   !< m, extra reach of the candidate lists beyond the search margin
    real(rk) :: reach_built = -1           !< m, reach of the current lists (< 0: none, search again)
    integer :: quiet_passes = 0            !< cycle passes since the surfaces last changed (erosion)
    real(rk), allocatable :: x_built(:,:)  !< (3, contact nodes) positions at the last full search
    real(rk), allocatable :: wide_lo(:,:), wide_hi(:,:)           !< (3, n_tri) boxes of the last full search
    integer, allocatable :: cand_start(:), cand(:)                 !< CSR over slave nodes: candidate triangles
    integer, allocatable :: cand_tri(:)    !< every triangle in some candidate list, ascending (their boxes are the pass's)
    integer :: n_cand_tri = 0
    logical, allocatable :: tri_mark(:)    !< (n_tri) work of the full search
    ! the full search's grid holds only the triangles near this rank's own
    ! slave nodes (sub_tri, ascending; their widened boxes)
    integer :: n_sub = 0
    integer, allocatable :: sub_tri(:)
    real(rk), allocatable :: sub_lo(:,:), sub_hi(:,:)
    integer :: full_searches = 0, passes = 0   !< counters for the log
    integer(i8) :: sweeps = 0              !< velocity-matching passes over the slave nodes, all cycles (log)
    integer :: sweep_limit_hits = 0        !< cycles that ended their passes at `iterations` unconverged (log)
    ! work arrays of the pass, sized once (no allocation in the cycle)
    real(rk), allocatable :: box_lo(:,:), box_hi(:,:)            !< (3, n_tri) widened bounding boxes
    ! edge-to-edge contact (&contact edges): the feature edges of the two
    ! surfaces (contact-node pairs), a grid over the master edges' boxes
    logical :: edges = .false.
    integer, allocatable :: slave_tri(:,:)            !< (3, n) the slave surface (its edges)
    integer, allocatable :: edge_m(:,:), edge_s(:,:)  !< (2, n) master and slave feature edges
    real(rk), allocatable :: edge_lo(:,:), edge_hi(:,:)   !< (3, master edges) widened boxes
    type(bucket_grid_t) :: edge_grid
    integer :: n_edge_contacts = 0         !< edge pairs corrected in the last cycle
    integer(i8) :: edge_contacts_total = 0 !< the same, summed over the run (log)
    real(rk) :: edge_max_depth = 0         !< m, deepest edge crossing found in the run (log)
    integer :: n_pass = 0                  !< slave nodes found by the current pass (active(1:n_pass))
    integer, allocatable :: active(:), on_tri(:), slot(:)          !< slave nodes found, their triangles, slave index
    real(rk), allocatable :: normal(:,:), area(:,:), share(:,:)    !< (3, n_slave)
    real(rk), allocatable :: dn_sum(:), t_sum(:,:)                 !< m/s, normal and tangential velocity changes so far in the cycle
    real(rk), allocatable :: room(:)       !< m, how far each found node may still be returned in this pass
    ! the last cycle
    real(rk) :: normal_impulse = 0, friction_impulse = 0   !< N s
    real(rk) :: master_impulse(3) = 0      !< N s, momentum the slave nodes gave the master side
    integer :: n_active = 0                !< slave nodes corrected
    real(rk) :: max_depth = 0              !< m, deepest penetration found (before the correction)
    real(rk) :: max_slip = 0               !< m/s, largest relative tangential velocity left at a contact point
    integer :: n_deep = 0                  !< slave nodes found deeper than the search margin (inside a master element)
    ! the whole run (log)
    integer(i8) :: deep_total = 0          !< deep slave nodes found, summed over the passes
    integer(i8) :: valley_total = 0        !< slave nodes matched to a valley's second face, summed over the passes (log)
    integer :: deep_passes = 0             !< passes that found any
    real(rk) :: deep_max = 0               !< m, the deepest of them
  end type

  type, public :: contact_t
    integer :: n_interfaces = 0
    type(interface_t), allocatable :: ifc(:)
    integer :: n_nodes = 0                 !< contact nodes: every master-triangle node and slave node
    !> the mesh's contact nodes (1..n_mesh); beyond them, contact node
    !> n_mesh + q is particle q (eroded = 'particles'), a slave node of the
    !> interfaces whose slave part is its part
    integer :: n_mesh = 0
    integer, allocatable :: particle_part(:)   !< (particles) the part each particle's element belonged to
    logical, allocatable :: part_converts(:)   !< (parts) its eroded elements become particles (its free nodes have no mass)
    logical, allocatable :: part_voids(:)      !< (parts) its eroded elements are closed voids (&contact voids; udar_eroded_voids)
    !> particles 1..particles_placed have been looked for inside the master
    !> bodies (place_new_particles); the run's count of those found inside,
    !> of those left inside (no surface face within reach) and the deepest (m)
    integer :: particles_placed = 0, particles_inside = 0, particles_left_inside = 0
    real(rk) :: particle_inside_deepest = 0
    integer, allocatable :: gidx(:)        !< their global node indices, ascending
    real(rk), allocatable :: x(:,:), v(:,:), m(:)   !< (3,n), (3,n), (n): gathered state, masses
    real(rk), allocatable :: x0(:,:)       !< (3,n) m, initial positions (the feature edges are judged on them)
    real(rk), allocatable :: h(:)     !< m, smallest altitude of each contact node's elements (bounds its returns)
    logical, allocatable :: returns(:)     !< the node can be returned (a slave node or a slave edge's): its h is kept
    integer, allocatable :: sym_planes(:)   !< bit p set: the node lies on symmetry plane p
    integer, allocatable :: plane_set(:)    !< the node's projector in plane_proj (0: on no plane)
    !> (3,3,0:sets) the motions each distinct set of symmetry planes allows
    !> a node (constrained_projection), built once at setup; 0: the identity
    real(rk), allocatable :: plane_proj(:,:,:)
    !> (4, planes) symmetry plane p (2D: line or axis): unit normal in 1:3,
    !> offset in 4. Across a face's edge (a segment's end) on one the
    !> surface goes on as its mirror image (faces_beside)
    real(rk), allocatable :: plane(:,:)
    integer, allocatable :: faces(:,:)     !< (3, n_faces) every face of a contact surface once
    real(rk), allocatable :: impulse(:)    !< N s, normal contact impulse on each contact node in the last pass
    real(rk), allocatable :: pressure(:)   !< Pa, work array: contact pressure of each contact node
    real(rk), allocatable :: work_area(:)  !< m2, work array of contact_pressure
    real(rk), allocatable :: v_sweep(:,:)  !< (3,n) m/s, work array: velocities at the start of a joint pass's sweep
    !> work arrays of a joint pass's solve with friction (3 joint_solve_rows square, and one column more)
    real(rk), allocatable :: joint_m(:,:), joint_work(:,:)
    !> work arrays of a joint pass's normal solve (joint_dense_rows square, and one column more)
    real(rk), allocatable :: lcp_m(:,:), lcp_work(:,:)
    !> (3, 0:3, joint_dense_rows) work array of the joint normal solve on
    !> symmetry planes: the direction each node of a row moves along
    real(rk), allocatable :: lcp_dir(:,:,:)
    logical, allocatable :: lcp_free(:)
    integer, allocatable :: node_row(:)    !< work array of row_components: 0 for every contact node between uses
    !> the rows of a pass's matching (match_passes) in the order of their
    !> sets (rows joined by shared nodes): set c is rows set_start(c) to
    !> set_start(c+1) - 1; row p is slave node active(row_k(p)) of
    !> interface row_ifc(p), its nodes, weights, coefficients and normal
    !> row_node(0:3,p), row_w, row_coef, row_nrm (contact_driver's row_data)
    integer, allocatable :: row_node(:,:), row_ifc(:), row_k(:), set_start(:)
    real(rk), allocatable :: row_w(:,:), row_coef(:,:), row_nrm(:,:)
    !> work arrays of the sets: the rows in the pass's order, their nodes and sets
    integer, allocatable :: found_node(:,:), found_ifc(:), found_k(:), found_set(:)
    !> each set's sweeps and whether it converged; on several ranks the
    !> sets' answers gathered (match_passes): counts per rank, buffers
    integer, allocatable :: set_sweeps(:)
    logical, allocatable :: set_converged(:)
    integer, allocatable :: set_counts(:)
    real(rk), allocatable :: set_send(:), set_recv(:)
    real(rk) :: dt_last = 0                !< s, the step of the last pass
    ! eroding surfaces: every tetrahedron of the parts whose boundary changes
    ! as elements erode (all their nodes are contact nodes)
    integer :: n_tets = 0
    integer, allocatable :: tet(:,:)       !< (4, n_tets) contact-node indices
    integer, allocatable :: tet_part(:), tet_gidx(:)   !< part, global element index (ascending)
    integer, allocatable :: tet_nbr(:,:)   !< (4, n_tets) tetrahedron across the face opposite each corner, 0 = none
    logical, allocatable :: tet_alive(:)
    !> CSR over contact nodes: the eroding parts' tetrahedra at each node
    !> (the exit step tests a node against every element at a vertex)
    integer, allocatable :: node_tet_ptr(:), node_tet(:)
    integer, allocatable :: fixed_faces(:,:)   !< (3, n) faces of the surfaces that do not erode
    integer, allocatable :: alive_count(:) !< work: alive tetrahedra at each contact node
    ! this rank's share
    integer, allocatable :: local(:)       !< local node of each contact node, 0 if not on this rank
    integer, allocatable :: owned_pos(:)   !< contact nodes this rank owns (their positions in gidx)
    integer, allocatable :: gather_pos(:)  !< position in gidx of each entry of the gathered buffer
    integer, allocatable :: counts(:)      !< reals each rank sends (7 per owned contact node)
    real(rk), allocatable :: send(:), recv(:)
    ! the search and the returns are shared out: each rank searches for its
    ! share of the slave nodes (interface_t mine) and the found ones go to
    ! every rank as records
    real(rk), allocatable :: rec_send(:), rec_recv(:)
    integer, allocatable :: rec_counts(:), rec_next(:), rec_end(:)   !< (0:ranks-1) reals from each rank, merge positions
    ! the neighbourhood: each cycle a rank gets the state of the contact
    ! nodes near its share of the slave nodes, not of all (stamp: the
    ! exchange's number; fresh(p) = stamp when node p's state is current)
    integer :: stamp = 0
    integer, allocatable :: fresh(:)
    real(rk) :: size_local = 0             !< m, largest extent of the local triangles at the start of the step
    logical :: full_state = .false.        !< edge-to-edge contact: every rank gets every contact node
    real(rk), allocatable :: x_send(:), x_recv(:), regions(:)
    ! where the pass's time goes on this rank (s, the run): the exchanges
    ! between ranks, the search for its share, the work every rank repeats
    ! (matching the velocities, returns, edges)
    real(rk) :: seconds_exchange = 0, seconds_search = 0, seconds_replicated = 0
    real(rk) :: seconds_matching = 0   !< s, of the velocity matching (each rank its sets)
    integer, allocatable :: x_counts(:), x_rcounts(:), region_counts(:)
    real(rk), allocatable :: v_prev(:,:), v_pre(:,:)   !< (3, owned contact nodes) m/s: v(n-1/2), v(n+1/2) before the pass
  end type
contains

  !> Whether any interface has an eroding surface: the contact that still
  !> asks for a dt_safety of 0.5 or less (doc/validation.md 4s, 4t); the
  !> others run at the elements' own step.
  pure logical function any_eroding(ct)
    type(contact_t), intent(in) :: ct
    integer :: i
    any_eroding = .false.
    do i = 1, ct%n_interfaces
      if (ct%ifc(i)%master_part > 0 .or. ct%ifc(i)%slave_part > 0) any_eroding = .true.
    end do
  end function

  !> Whether face tri (a triangle, or a 2D segment) lies on a symmetry plane
  !> (line, or the axis), given each node's bit set of planes (sym_planes,
  !> indexed like tri): the mirrored body continues there, it is no contact
  !> surface.
  pure logical function on_symmetry_plane(sym_planes, tri)
    integer, intent(in) :: sym_planes(:), tri(:)
    integer :: bits, a
    bits = sym_planes(tri(1))
    do a = 2, size(tri)
      bits = iand(bits, sym_planes(tri(a)))
    end do
    on_symmetry_plane = bits /= 0
  end function

  !> Room for n contact nodes (the new ones beyond the old count: particles,
  !> no mesh node, at rest and massless until set).
  subroutine contact_grow_nodes(ct, n)
    type(contact_t), intent(inout) :: ct
    integer, intent(in) :: n
    integer :: i, old
    old = ct%n_nodes
    if (n <= old) return
    call grow2(ct%x); call grow2(ct%v); call grow2(ct%x0); call grow2(ct%v_sweep);
    call grow1(ct%m); call grow1(ct%h, huge(1.0_rk)); call grow1(ct%impulse); call grow1(ct%pressure)
    call grow1(ct%work_area)
    call growi(ct%gidx); call growi(ct%sym_planes); call growi(ct%plane_set); call growi(ct%alive_count); call growi(ct%local)
    call growi(ct%fresh); call growi(ct%node_row)
    call growl(ct%returns)
    do i = 1, ct%n_interfaces
      call grow2(ct%ifc(i)%x_built)
      call growl(ct%ifc(i)%near)
      ! the candidate lists know only the old nodes: search again
      ct%ifc(i)%reach_built = -1.0_rk
    end do
    ct%n_nodes = n
  contains
    subroutine grow2(a)
      real(rk), allocatable, intent(inout) :: a(:,:)
      real(rk), allocatable :: t(:,:)
      if (.not. allocated(a)) return
      allocate(t(size(a, 1), n), source=0.0_rk)
      t(:,1:old) = a(:,1:old)
      call move_alloc(t, a)
    end subroutine
    subroutine grow1(a, fill)
      real(rk), allocatable, intent(inout) :: a(:)
      real(rk), intent(in), optional :: fill
      real(rk), allocatable :: t(:)
      if (.not. allocated(a)) return
      allocate(t(n), source=0.0_rk)
      if (present(fill)) t = fill
      t(1:old) = a(1:old)
      call move_alloc(t, a)
    end subroutine
    subroutine growi(a)
      integer, allocatable, intent(inout) :: a(:)
      integer, allocatable :: t(:)
      if (.not. allocated(a)) return
      allocate(t(n), source=0)
      t(1:old) = a(1:old)
      call move_alloc(t, a)
    end subroutine
    subroutine growl(a)
      logical, allocatable, intent(inout) :: a(:)
      logical, allocatable :: t(:)
      if (.not. allocated(a)) return
      allocate(t(n), source=.false.)
      t(1:old) = a(1:old)
      call move_alloc(t, a)
    end subroutine
  end subroutine

  !> ct%returns: the slave nodes and the slave edges' nodes of every
  !> interface (the nodes whose altitude bounds a return).
  subroutine mark_returns(ct)
    type(contact_t), intent(inout) :: ct
    integer :: i
    if (.not. allocated(ct%returns)) allocate(ct%returns(ct%n_nodes))
    ct%returns = .false.
    do i = 1, ct%n_interfaces
      ct%returns(ct%ifc(i)%slave) = .true.
      if (allocated(ct%ifc(i)%edge_s)) ct%returns(reshape(ct%ifc(i)%edge_s, [size(ct%ifc(i)%edge_s)])) = .true.
    end do
  end subroutine

  !> Which slave nodes this rank searches for (mine): the slave list in
  !> Morton order of the nodes' initial positions x0, cut into equal runs,
  !> one per rank: a balanced and compact share whatever the partition of
  !> the mesh (a projectile's surface is usually on one rank). The results
  !> do not depend on it.
  subroutine assign_slaves(it, x0, rank, n_ranks)
    type(interface_t), intent(inout) :: it
    real(rk), intent(in) :: x0(:,:)
    integer, intent(in) :: rank, n_ranks
    integer(i8), allocatable :: keys(:)
    integer, allocatable :: perm(:)
    integer :: ns, first, last, q
    ns = size(it%slave)
    if (allocated(it%mine)) deallocate(it%mine)
    if (allocated(it%exited)) deallocate(it%exited)
    if (allocated(it%searcher)) deallocate(it%searcher)
    allocate(it%mine(ns), source=.false.)
    allocate(it%exited(ns), source=.false.)
    allocate(it%searcher(ns), source=0)
    it%local_tri_valid = .false.
    if (ns == 0) return
    allocate(keys(ns), perm(ns))
    call morton_keys(transpose(x0(:, it%slave)), keys)
    call stable_sort_permutation(keys, perm)
    do q = 0, n_ranks - 1
      first = int(int(ns, i8)*q/n_ranks) + 1
      last = int(int(ns, i8)*(q + 1)/n_ranks)
      it%searcher(perm(first:last)) = q
    end do
    it%mine = it%searcher == rank
  end subroutine

  !> The interface's work arrays hold its current triangles and slave nodes
  !> (grown by half again when too small: no allocation in a steady run).
  subroutine size_interface_work(it)
    type(interface_t), intent(inout) :: it
    integer :: nt, ns
    nt = size(it%tri, 2)
    ns = size(it%slave)
    if (allocated(it%box_lo)) then
      if (size(it%box_lo, 2) < nt) deallocate(it%box_lo, it%box_hi, it%wide_lo, it%wide_hi, it%cand_tri, it%tri_mark, &
                                              it%sub_tri, it%sub_lo, it%sub_hi)
    end if
    if (.not. allocated(it%box_lo)) then
      nt = max(nt, 3*size(it%tri, 2)/2)
      allocate(it%box_lo(3,nt), it%box_hi(3,nt), it%wide_lo(3,nt), it%wide_hi(3,nt), it%cand_tri(nt), &
               it%sub_tri(nt), it%sub_lo(3,nt), it%sub_hi(3,nt))
      allocate(it%tri_mark(nt), source=.false.)
    end if
    if (allocated(it%active)) then
      if (size(it%active) < 2*ns) deallocate(it%active, it%on_tri, it%slot, it%cand_start, it%normal, it%area, &
                                           it%share, it%dn_sum, it%t_sum, it%room)
    end if
    if (.not. allocated(it%active)) then
      ns = max(ns, 3*size(it%slave)/2)
      ! up to two faces a slave node (a valley of the master surface)
      allocate(it%active(2*ns), it%on_tri(2*ns), it%slot(2*ns), it%cand_start(ns + 1), it%normal(3,2*ns), it%area(3,2*ns), &
               it%share(3,2*ns), it%dn_sum(2*ns), it%t_sum(3,2*ns), it%room(2*ns))
    end if
    if (.not. allocated(it%cand)) allocate(it%cand(4*size(it%slave) + 1))
  end subroutine

  !> The face across each edge of every face of the interface's current
  !> master surface (it%across; after every rebuild of it%tri): the
  !> contact asks for it for every face a node is behind, so it is looked
  !> up, not searched. No sort: it is redone at every erosion. x0: the
  !> contact nodes' initial positions (where an edge has more than two
  !> faces, they decide which face bounds the same solid wedge).
  subroutine surface_neighbours(it, x0)
    type(interface_t), intent(inout) :: it
    real(rk), intent(in) :: x0(:,:)
    integer, allocatable :: tri_start(:), tri_at(:)
    integer :: nn, t, a
    nn = 0
    if (size(it%tri, 2) > 0) nn = maxval(it%tri)
    call node_triangles(it%tri, nn, tri_start, tri_at)
    if (allocated(it%across)) deallocate(it%across)
    allocate(it%across(size(it%tri, 1), size(it%tri, 2)))
    do t = 1, size(it%tri, 2)
      do a = 1, size(it%tri, 1)
        it%across(a,t) = face_across(it%tri, tri_start, tri_at, t, a, x0)
      end do
    end do
  end subroutine

  !> The triangles at each of n_nodes nodes (CSR: at(start(n):start(n+1)-1),
  !> ascending) of a surface tri.
  pure subroutine node_triangles(tri, n_nodes, start, at)
    integer, intent(in) :: tri(:,:), n_nodes
    integer, allocatable, intent(out) :: start(:), at(:)
    integer, allocatable :: fill(:)
    integer :: t, a, i
    allocate(start(n_nodes + 1), source=0)
    do t = 1, size(tri, 2)
      start(tri(:,t) + 1) = start(tri(:,t) + 1) + 1
    end do
    start(1) = 1
    do i = 1, n_nodes
      start(i+1) = start(i+1) + start(i)
    end do
    allocate(at(start(n_nodes+1) - 1), fill(n_nodes))
    fill = start(1:n_nodes)
    do t = 1, size(tri, 2)
      do a = 1, size(tri, 1)
        i = tri(a,t)
        at(fill(i)) = t
        fill(i) = fill(i) + 1
      end do
    end do
  end subroutine

  !> The triangle across the edge of triangle t opposite its corner a, or
  !> in 2D the segment across the end of segment t opposite its node a (0: a
  !> rim, or an edge or end of more than two faces): surface_neighbours'
  !> table.
  pure integer function neighbour_across(it, t, a)
    type(interface_t), intent(in) :: it
    integer, intent(in) :: t, a
    neighbour_across = it%across(a,t)
  end function

  !> What neighbour_across gives, from the faces at each node (CSR
  !> tri_start, tri_at of node_triangles). Where more than two faces share
  !> the edge (3D) or end (2D) -- two bodies, or two parts of an eroding
  !> one, touching along an edge only -- the face across is the one that
  !> bounds the same solid wedge: of those that run the edge the other way
  !> (a consistently oriented neighbour), the first met turning from t
  !> about the edge into its body (behind its plane), in the initial
  !> positions x0, where the elements around the edge do not overlap.
  !> 0: a rim, or no such face.
  pure integer function face_across(tri, tri_start, tri_at, t, a, x0) result(found)
    integer, intent(in) :: tri(:,:), tri_start(:), tri_at(:), t, a
    real(rk), intent(in) :: x0(:,:)
    integer :: i, j, k, s, n_found, nf, c
    real(rk) :: e(3), n_t(3), w_t(3), w(3), turn, best_turn, xt(3,3), d_unused, g_unused(3)
    real(rk), parameter :: two_pi = 8.0_rk*atan(1.0_rk)
    nf = size(tri, 1)
    if (nf == 3) then
      i = tri(mod(a,3)+1,t)
      j = tri(mod(a+1,3)+1,t)
    else
      i = tri(3-a,t)
      j = i
    end if
    found = 0
    n_found = 0
    do k = tri_start(i), tri_start(i+1) - 1
      s = tri_at(k)
      if (s == t .or. all(tri(:,s) /= j)) cycle
      n_found = n_found + 1
      found = s
    end do
    if (n_found <= 1) return
    ! the wedge's turn: from t's inward direction w_t (in its plane, away
    ! from the edge, or in 2D along the segment) toward -n_t (its outward
    ! normal, as the contact's projection has it)
    do c = 1, nf
      xt(:,c) = x0(:,tri(c,t))
    end do
    call face_projection(xt(:,1:nf), x0(:,tri(a,t)), n_t, d_unused, g_unused)
    if (nf == 3) then
      e = x0(:,j) - x0(:,i)
      e = e/norm2(e)
      w_t = across_edge(x0(:,tri(a,t)))
    else
      w_t = x0(:,tri(a,t)) - x0(:,i)
      w_t = w_t/norm2(w_t)
    end if
    found = 0
    best_turn = huge(1.0_rk)
    do k = tri_start(i), tri_start(i+1) - 1
      s = tri_at(k)
      if (s == t .or. all(tri(:,s) /= j)) cycle
      if (.not. runs_back(s)) cycle
      if (nf == 3) then
        w = across_edge(x0(:,sum(tri(:,s)) - i - j))
      else
        w = x0(:,sum(tri(:,s)) - i) - x0(:,i)
        w = w/norm2(w)
      end if
      turn = atan2(dot_product(w, -n_t), dot_product(w, w_t))
      if (turn <= 0.0_rk) turn = turn + two_pi
      if (turn < best_turn) then
        best_turn = turn
        found = s
      end if
    end do

  contains

    !> The unit direction from the edge i-j toward point p, square to the edge.
    pure function across_edge(p) result(d)
      real(rk), intent(in) :: p(3)
      real(rk) :: d(3)
      d = p - x0(:,i)
      d = d - dot_product(d, e)*e
      d = d/norm2(d)
    end function

    !> Whether face s runs t's edge (end) the other way: j before i in its
    !> cyclic order (2D: i at the other end).
    pure logical function runs_back(s)
      integer, intent(in) :: s
      integer :: c
      if (nf == 3) then
        do c = 1, 3
          if (tri(c,s) == j) exit
        end do
        runs_back = tri(mod(c,3)+1,s) == i
      else
        runs_back = (tri(1,t) == i .and. tri(2,s) == i) .or. (tri(2,t) == i .and. tri(1,s) == i)
      end if
    end function
  end function

  !> The feature edges of a surface (triangles tri, contact nodes at x):
  !> every edge of one triangle only (a rim), and every edge of two whose
  !> faces meet convexly at more than 30 degrees (a body's edge, where a
  !> crossing edge can pass between the nodes). Each once, as (lower node,
  !> higher node), ascending.
  function feature_edges(tri, x) result(edges)
    integer, intent(in) :: tri(:,:)
    real(rk), intent(in) :: x(:,:)
    integer, allocatable :: edges(:,:)
    integer, allocatable :: key(:,:), order(:)
    real(rk), allocatable :: nrm(:,:)
    real(rk), parameter :: cos_limit = 0.866_rk   ! 30 degrees
    integer :: t, a, m, i, j, n_e, t1, t2, opp
    logical :: keep
    m = size(tri, 2)
    allocate(key(4, 3*m), nrm(3, m))
    do t = 1, m
      nrm(:,t) = cross(x(:,tri(2,t)) - x(:,tri(1,t)), x(:,tri(3,t)) - x(:,tri(1,t)))
      nrm(:,t) = nrm(:,t)/max(norm2(nrm(:,t)), tiny(1.0_rk))
      do a = 1, 3
        i = tri(a,t)
        j = tri(mod(a,3)+1,t)
        key(:, 3*(t-1)+a) = [min(i,j), max(i,j), t, tri(mod(a+1,3)+1,t)]   ! edge, its face, the third node
      end do
    end do
    ! sorted by (lower, higher) node
    allocate(order(3*m))
    call stable_sort_permutation(int(key(1,:), i8)*(maxval(key(2,:)) + 1_i8) + key(2,:), order)
    allocate(edges(2, 3*m))
    n_e = 0
    i = 1
    do while (i <= 3*m)
      j = i
      do while (j < 3*m)
        if (any(key(1:2,order(j+1)) /= key(1:2,order(i)))) exit
        j = j + 1
      end do
      keep = j == i                           ! a rim
      if (j == i + 1) then
        t1 = key(3,order(i))
        t2 = key(3,order(j))
        opp = key(4,order(j))                 ! the other face's third node: behind the first face at a convex edge
        keep = dot_product(nrm(:,t1), nrm(:,t2)) < cos_limit .and. &
               dot_product(nrm(:,t1), x(:,opp) - x(:,key(1,order(i)))) < 0.0_rk
      end if
      if (keep) then
        n_e = n_e + 1
        edges(:,n_e) = key(1:2,order(i))
      end if
      i = j + 1
    end do
    edges = edges(:, 1:n_e)
  end function

  !> Self-contact: for every slave node the contact nodes within two edges
  !> of it along the current surface (it%tri), ascending: the
  !> neighbourhood it cannot be in contact with. n_nodes: contact nodes.
  subroutine self_neighbourhoods(it, n_nodes)
    type(interface_t), intent(inout) :: it
    integer, intent(in) :: n_nodes
    integer, allocatable :: tri_start(:), tri_of(:), ring1(:)
    logical, allocatable :: mark(:)
    integer :: k, j, n_ring, n1, pass
    call node_triangles(it%tri, n_nodes, tri_start, tri_of)
    allocate(mark(n_nodes), source=.false.)
    if (allocated(it%ring_start)) deallocate(it%ring_start, it%ring)
    allocate(it%ring_start(size(it%slave) + 1), ring1(64))
    ! twice: count, then fill
    do pass = 1, 2
      it%ring_start(1) = 1
      do k = 1, size(it%slave)
        ! first ring: the nodes of the triangles at the slave node; second: of theirs
        n_ring = 0
        call add_nodes_of_triangles_at(it%slave(k))
        n1 = n_ring
        do j = 1, n1
          call add_nodes_of_triangles_at(ring1(j))
        end do
        mark(ring1(1:n_ring)) = .false.
        if (pass == 2) it%ring(it%ring_start(k):it%ring_start(k) + n_ring - 1) = ring1(1:n_ring)
        it%ring_start(k+1) = it%ring_start(k) + n_ring
      end do
      if (pass == 1) allocate(it%ring(it%ring_start(size(it%slave) + 1) - 1))
    end do
    if (allocated(it%touched)) deallocate(it%touched)
    allocate(it%touched(size(it%slave)), source=.false.)   ! the slave list changed
    if (.not. allocated(it%near)) allocate(it%near(n_nodes), source=.false.)
    if (size(it%near) < n_nodes) then
      deallocate(it%near)
      allocate(it%near(n_nodes), source=.false.)
    end if

  contains

    subroutine add_nodes_of_triangles_at(p)
      integer, intent(in) :: p
      integer :: jj, aa, q
      integer, allocatable :: grown(:)
      do jj = tri_start(p), tri_start(p+1) - 1
        do aa = 1, size(it%tri, 1)
          q = it%tri(aa, tri_of(jj))
          if (mark(q)) cycle
          mark(q) = .true.
          n_ring = n_ring + 1
          if (n_ring > size(ring1)) then
            allocate(grown(2*size(ring1)))
            grown(1:size(ring1)) = ring1
            call move_alloc(grown, ring1)
          end if
          ring1(n_ring) = q
        end do
      end do
    end subroutine
  end subroutine

end module udar_contact_model
