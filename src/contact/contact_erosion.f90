!> Eroding contact: as elements of an eroding part erode, the faces they
!> leave exposed join the part's contact surface, the faces they took with
!> them leave it, and nodes left without elements (debris) stay slave
!> nodes that still strike master surfaces. Every rank applies the same
!> list of eroded elements to the same replicated surfaces, so the surfaces
!> (and the contact pass) stay the same on any number of ranks.
module udar_contact_erosion
  use udar_ordering, only: find_sorted
  use udar_comms, only: comms_rank, comms_size
  use udar_contact_model, only: contact_t, interface_t, size_interface_work, surface_neighbours, on_symmetry_plane, self_neighbourhoods, &
                                assign_slaves, mark_returns
  use udar_contact_setup, only: element_face, contact_edges
  implicit none
  private
  public :: contact_erode, contact_eroding_surfaces

contains

  !> Elements eroded (global element indices, the same list on every rank):
  !> marks those of the eroding parts and rebuilds the surfaces of the
  !> interfaces whose parts lost one.
  subroutine contact_erode(ct, eroded)
    type(contact_t), intent(inout) :: ct
    integer, intent(in) :: eroded(:)
    logical, allocatable :: part_changed(:)
    integer :: i, t
    if (ct%n_tets == 0 .or. size(eroded) == 0) return
    allocate(part_changed(maxval(ct%tet_part)), source=.false.)
    do i = 1, size(eroded)
      t = tet_index(eroded(i))
      if (t == 0) cycle
      if (.not. ct%tet_alive(t)) cycle
      ct%tet_alive(t) = .false.
      part_changed(ct%tet_part(t)) = .true.
    end do
    if (any(part_changed)) call rebuild_surfaces(ct, part_changed)

  contains

    !> Index in ct%tet of global element g (ascending tet_gidx), 0 if none.
    integer function tet_index(g)
      integer, intent(in) :: g
      tet_index = find_sorted(ct%tet_gidx(1:ct%n_tets), g)
    end function
  end subroutine

  !> The surfaces of the eroding parts from their tetrahedra (at start-up:
  !> the same triangles in the same order as the mesh's boundary, now with
  !> the fourth corner of each).
  subroutine contact_eroding_surfaces(ct)
    type(contact_t), intent(inout) :: ct
    logical, allocatable :: part_changed(:)
    if (ct%n_tets == 0) return
    allocate(part_changed(maxval(ct%tet_part)), source=.true.)
    call rebuild_surfaces(ct, part_changed)
  end subroutine

  !> The current boundary of the parts that changed, into the interfaces
  !> and the pressure's face list.
  subroutine rebuild_surfaces(ct, part_changed)
    type(contact_t), intent(inout) :: ct
    logical, intent(in) :: part_changed(:)
    integer, allocatable :: faces(:,:), face_part(:), face_apex(:), sel(:)
    integer :: i, t, k, f, n, n_fixed, nc
    ! corners of an element: 4 (tetrahedra) or 3 (2D triangles, whose faces are segments)
    nc = size(ct%tet, 1)
    ! alive tetrahedra at each node: 0 = a free node (debris)
    ct%alive_count = 0
    do t = 1, ct%n_tets
      if (ct%tet_alive(t)) ct%alive_count(ct%tet(:,t)) = ct%alive_count(ct%tet(:,t)) + 1
    end do
    ! the current boundary of every eroding part, in one sweep: exposed faces
    ! of alive tetrahedra in ascending element and face order (the order of
    ! the initial surface), counter-clockwise seen from outside
    n = 0
    do t = 1, ct%n_tets
      do f = 1, nc
        if (exposed(t, f)) n = n + 1
      end do
    end do
    allocate(faces(nc - 1, n), face_part(n), face_apex(n))
    n = 0
    do t = 1, ct%n_tets
      do f = 1, nc
        if (.not. exposed(t, f)) cycle
        n = n + 1
        faces(:,n) = ct%tet(element_face(nc, f), t)
        face_part(n) = ct%tet_part(t)
        face_apex(n) = ct%tet(f, t)
      end do
    end do
    do k = 1, ct%n_interfaces
      associate (it => ct%ifc(k))
        if (.not. (changed(it%master_part) .or. changed(it%slave_part))) cycle
        if (it%self) then
          ! the part's boundary (exposed: no face on a symmetry plane); its nodes and free nodes
          it%tri = faces(:, pack([(i, i = 1, n)], face_part == it%master_part))
          if (allocated(it%apex)) deallocate(it%apex)
          allocate(it%apex(size(it%tri, 2)), source=0)    ! self-contact: only what crosses in a cycle
          it%slave = slave_nodes(it%slave_part, it%tri)
          call self_neighbourhoods(it, ct%n_nodes)
        else
          if (it%master_part > 0) then
            sel = pack([(i, i = 1, n)], face_part == it%master_part)
            it%tri = faces(:, sel)
            it%apex = face_apex(sel)
          end if
          if (it%slave_part > 0) it%slave = slave_nodes(it%slave_part, particles_only=it%own_particles)
          if (it%edges) then
            ! new edges appear as elements erode
            if (it%slave_part > 0) it%slave_tri = faces(:, pack([(i, i = 1, n)], face_part == it%slave_part))
            call contact_edges(it, ct%x0)
          end if
        end if
        call size_interface_work(it)
        if (it%seams .or. it%sharp_edges) call surface_neighbours(it, ct%x0)
        call assign_slaves(it, ct%x0, comms_rank(), comms_size())
        it%reach_built = -1.0       ! a full search on the new surfaces
        it%quiet_passes = 0
      end associate
    end do
    call mark_returns(ct)
    ! faces for the contact pressure: the fixed ones and the eroding parts' current ones
    n_fixed = size(ct%fixed_faces, 2)
    deallocate(ct%faces)
    allocate(ct%faces(nc - 1, n_fixed + n))
    ct%faces(:,1:n_fixed) = ct%fixed_faces
    ct%faces(:,n_fixed+1:) = faces


  contains

    logical function changed(ip)
      integer, intent(in) :: ip
      changed = .false.
      if (ip > 0) changed = part_changed(ip)
    end function

    !> Whether face f of element t is on the current boundary (not on a
    !> symmetry plane, 2D: the axis or a symmetry line, where the body continues).
    logical function exposed(t, f)
      integer, intent(in) :: t, f
      exposed = ct%tet_alive(t)
      if (exposed .and. ct%tet_nbr(f,t) > 0) exposed = .not. ct%tet_alive(ct%tet_nbr(f,t))
      if (exposed) exposed = .not. on_symmetry_plane(ct%sym_planes, ct%tet(element_face(nc, f), t))
    end function

    !> Slave nodes of part ip: the nodes of its current boundary (or of the
    !> faces own) and its free nodes and particles, ascending; particles_only: its particles alone.
    function slave_nodes(ip, own, particles_only) result(nodes)
      integer, intent(in) :: ip
      integer, intent(in), optional :: own(:,:)   !< (self-contact) the nodes of these faces instead
      logical, intent(in), optional :: particles_only   !< only its particles
      integer, allocatable :: nodes(:)
      logical, allocatable :: mark(:)
      integer :: j, c, t
      logical :: mesh_nodes
      allocate(mark(ct%n_nodes), source=.false.)
      mesh_nodes = .true.
      if (present(particles_only)) mesh_nodes = .not. particles_only
      if (.not. mesh_nodes) then
        ! only the particles below
      else if (present(own)) then
        do j = 1, size(own, 2)
          mark(own(:,j)) = .true.
        end do
      else
        do j = 1, n
          if (face_part(j) == ip) mark(faces(:,j)) = .true.
        end do
      end if
      ! free nodes keep the mass of their eroded elements, unless those
      ! became particles (which are slave nodes instead)
      if (mesh_nodes .and. .not. ct%part_converts(ip)) then
        do t = 1, ct%n_tets
          if (ct%tet_part(t) /= ip) cycle
          do c = 1, nc
            if (ct%alive_count(ct%tet(c,t)) == 0) mark(ct%tet(c,t)) = .true.
          end do
        end do
      end if
      do j = 1, ct%n_nodes - ct%n_mesh
        if (ct%particle_part(j) == ip) mark(ct%n_mesh + j) = .true.
      end do
      nodes = pack([(j, j = 1, ct%n_nodes)], mark)
    end function
  end subroutine
end module udar_contact_erosion
