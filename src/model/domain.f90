!> The mesh and state of one rank, structure of arrays; nd_ = node, el_ =
!> element. Global order is the mesh's space-filling-curve numbering (the
!> same on every rank). On a rank, nodes are its owned ones (1..n_owned_nodes)
!> then its ghosts, each ascending in global index; elements are ascending in
!> global index, owned and ghost interleaved (el_owned). With one rank the
!> local and global numberings coincide.
module udar_domain
  use udar_kinds, only: rk, i8, max_name_len, block_size
  use udar_config, only: material_cfg_t, geometry_solid
  implicit none
  private
  public :: domain_t, wall_t, block_size, domain_bytes, gauge_node, gauge_element, gauge_point

  !> what a gauge follows (domain_t%gauge_kind)
  integer, parameter :: gauge_node = 1, gauge_element = 2, gauge_point = 3

  type :: wall_t
    real(rk) :: point(3) = 0.0_rk, normal(3) = 0.0_rk
    integer :: wall_type = 1
    real(rk) :: friction = 0.0_rk     !< -, Coulomb coefficient (wall_coulomb)
  end type

  type :: domain_t
    ! ---- distribution
    integer :: n_global_nodes = 0, n_global_elems = 0
    integer :: n_owned_nodes = 0                 !< nodes whose update this rank computes
    integer, allocatable :: nd_gidx(:), el_gidx(:)   !< 1-based global index of each local node / element
    logical, allocatable :: el_owned(:)
    integer, allocatable :: el_owned_list(:)     !< local indices of the owned elements, ascending
    ! ---- nodes
    integer :: n_nodes = 0
    integer, allocatable :: nd_id(:)            !< mesh-file node tag
    integer, allocatable :: nd_part(:)          !< part of the lowest-id incident element
    !> (3,n): m, m, m/s, N. Components interleaved: an element's gather of a node
    !> reads one cache line, not three.
    real(rk), allocatable :: nd_x0(:,:), nd_x(:,:), nd_v(:,:), nd_f(:,:)
    real(rk), allocatable :: nd_mass(:)         !< kg, lumped
    real(rk), allocatable :: nd_vol0(:), nd_j(:)     !< m3, -: nodal reference volume and volume ratio (anti-locking)
    real(rk), allocatable :: nd_vref(:)   !< m3, the volume nd_j is taken against (nd_vol0, rebased at erosion)
    real(rk), allocatable :: nd_p(:)            !< Pa, nodal average pressure (anti-locking)
    real(rk), allocatable :: nd_k(:)            !< N/m, sum of the incident elements' stiffness bounds (time step)
    ! node -> incident elements, each list ascending in element id (fixed assembly order)
    integer, allocatable :: nd_el_ptr(:), nd_el(:), nd_el_corner(:)
    ! ---- elements
    integer :: n_elems = 0
    integer, allocatable :: el_id(:), el_part(:), el_mat(:)
    integer, allocatable :: el_conn(:,:)        !< (n,corners) node indices
    integer :: corners = 4                      !< nodes of an element: 4 (tet4) or 3 (2D tri3)
    real(rk) :: corner_share = 0.25_rk          !< 1/corners: each node's share of a lumped element quantity
    integer :: geometry = geometry_solid        !< udar_config geometry_*: 3D, axisymmetric or plane strain
    real(rk), allocatable :: el_vol0(:), el_vol(:), el_mass(:)   !< m3, m3, kg
    real(rk), allocatable :: el_h(:)   !< m, smallest altitude at the last update (huge when eroded)
    real(rk), allocatable :: el_k(:)   !< N/m, bound of the element stiffness's largest eigenvalue at the last
                                       !< update, times its viscosity factor (0 when eroded): the nodal time step
    real(rk), allocatable :: el_j(:)            !< -, volume ratio seen by the EOS (nodal-averaged with anti-locking)
    real(rk), allocatable :: el_e(:)            !< J/kg, specific internal energy
    real(rk), allocatable :: el_wp(:)           !< J/kg, specific plastic work
    real(rk), allocatable :: el_p(:), el_q(:)   !< Pa, EOS pressure and artificial viscosity
    real(rk), allocatable :: el_pavg(:)  !< Pa, stabilised: the pressure the element puts into the nodal average
                                         !< (recomputed every cycle before use: no restart state)
    real(rk), allocatable :: el_s(:,:)          !< (n,6) Pa, deviatoric stress xx,yy,zz,xy,yz,zx
    real(rk), allocatable :: el_eps_p(:), el_temp(:)  !< -, K
    real(rk), allocatable :: el_hard(:), el_soft(:)   !< Pa, -: strain-hardening part and thermal factor of the flow stress
    integer, allocatable :: el_state(:)         !< intact, fractured or eroded (udar_fracture)
    real(rk), allocatable :: el_damage(:)       !< -, fracture at 1 (eps_p/eps_f or Johnson-Cook damage)
    real(rk), allocatable :: el_eps_tot(:)      !< -, accumulated equivalent deviatoric (total) strain
    ! vectorized blocks: runs of consecutive elements of one material
    integer :: n_blocks = 0
    integer, allocatable :: blk_first(:), blk_last(:)
    !> clock ticks (system_clock) each block's stress update took, summed
    !> since the run or its last repartition: the elements' measured cost
    !> (&run rebalance_imbalance)
    integer(i8), allocatable :: blk_ticks(:)
    logical :: time_blocks = .false.         !< measure blk_ticks (only a run that may repartition)
    !> owned nodes by the block holding their last (highest-id) incident
    !> element: blk_nd(blk_nd_ptr(b):blk_nd_ptr(b+1)-1), ascending, are the
    !> nodes whose element lists are complete once block b is done, so an
    !> element pass can sum them (in the lists' fixed order) while the
    !> block's values are still in cache
    integer, allocatable :: blk_nd_ptr(:), blk_nd(:)
    ! ---- model
    type(material_cfg_t), allocatable :: mat(:)
    integer :: n_parts = 0
    character(len=max_name_len), allocatable :: part_name(:)
    real(rk), allocatable :: part_temp0(:)   !< K, each part's initial temperature
    ! ---- conditions: velocity constraints and rigid walls
    integer, allocatable :: fixed_nodes(:)
    integer, allocatable :: sym_nodes(:)        !< one entry per (node, plane)
    real(rk), allocatable :: sym_normal(:,:)    !< (n_sym,3)
    type(wall_t), allocatable :: walls(:)
    !> the symmetry planes as frictionless walls facing the body (their
    !> normals into it): what keeps particles, which are no mesh nodes, on
    !> the body's side, and across which they meet their mirror images
    !> (axisymmetric, the axis r = 0 is the last of them)
    type(wall_t), allocatable :: sym_walls(:)
    ! ---- gauges (&gauge): a node, an element or a material point (the
    ! element it starts in and its barycentric weights); global indices,
    ! and on each rank the local indices of what it owns (0: not here)
    character(len=max_name_len), allocatable :: gauge_name(:)
    integer, allocatable :: gauge_kind(:)
    integer, allocatable :: gauge_nodes(:,:)      !< (4,g) global node indices (a node gauge: the first)
    real(rk), allocatable :: gauge_w(:,:)         !< (4,g) the nodes' weights
    integer, allocatable :: gauge_elem(:)         !< global element index (0 for a node gauge)
    integer, allocatable :: gauge_nodes_loc(:,:)  !< (4,g) local index of each owned node, 0 elsewhere
    integer, allocatable :: gauge_elem_loc(:)     !< local index of the owned element, 0 elsewhere
    logical :: anti_locking = .true.             !< any nodal-averaged formulation (not the plain tet)
    integer :: tet_formulation = 2               !< udar_config tet_*: plain, nodal, stabilised, stabilised_linear
    real(rk) :: stab_beta = 0.0_rk        !< -, weight of the element's own volume ratio near its nodes' (stabilised only)
    real(rk) :: stab_beta_large = 0.0_rk  !< -, that weight at a large departure from the nodes
    real(rk) :: stab_onset = 1.0_rk       !< -, |ln(Je/Jbar)| from which the weight is stab_beta_large
    real(rk) :: q_linear = 0.06_rk, q_quadratic = 1.5_rk
    real(rk) :: erode_dt_limit = 0.0_rk          !< s, an eroding material's element with a smaller stable step is eroded
    !> whether the stress pass keeps el_vol (read only to rebase the nodal
    !> volumes after erosion) and el_h (read only by contact): without
    !> erosion or contact they stay as set up, 16 bytes per element-cycle
    !> of memory traffic less each
    logical :: keep_volumes = .true., keep_altitudes = .true.
  end type

contains

  !> Bytes held by the domain's arrays (memory reports; `make bench` divides
  !> it by the element count). Every allocatable component is listed here.
  pure integer(i8) function domain_bytes(d) result(b)
    type(domain_t), intent(in) :: d
    b = sum([bytes(d%nd_gidx), bytes(d%el_gidx), bytes(d%el_owned), bytes(d%el_owned_list), bytes(d%nd_id), &
             bytes(d%nd_part), bytes(d%nd_x0), bytes(d%nd_x), bytes(d%nd_v), bytes(d%nd_f), bytes(d%nd_mass), &
             bytes(d%nd_vol0), bytes(d%nd_j), bytes(d%nd_vref), bytes(d%nd_p), bytes(d%nd_k), bytes(d%nd_el_ptr), &
             bytes(d%nd_el), bytes(d%nd_el_corner), bytes(d%el_id), bytes(d%el_part), bytes(d%el_mat), &
             bytes(d%el_conn), bytes(d%el_vol0), bytes(d%el_vol), bytes(d%el_mass), bytes(d%el_h), &
             bytes(d%el_k), bytes(d%el_j), bytes(d%el_e), bytes(d%el_wp), bytes(d%el_p), bytes(d%el_q), &
             bytes(d%el_pavg), bytes(d%el_s), bytes(d%el_eps_p), bytes(d%el_temp), bytes(d%el_hard), &
             bytes(d%el_soft), bytes(d%el_state), bytes(d%el_damage), bytes(d%el_eps_tot), &
             bytes(d%blk_first), bytes(d%blk_last), bytes(d%blk_nd_ptr), bytes(d%blk_nd), bytes(d%blk_ticks), &
             bytes(d%fixed_nodes), bytes(d%sym_nodes), bytes(d%sym_normal)])
  contains
    !> Bytes of an array, 0 when it is not allocated (then it is absent).
    pure integer(i8) function bytes(a)
      class(*), intent(in), optional :: a(..)
      bytes = 0
      if (present(a)) bytes = size(a, kind=i8)*storage_size(a)/8
    end function
  end function
end module udar_domain
