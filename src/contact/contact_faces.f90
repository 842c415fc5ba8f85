!> The contact geometry of a master face, whatever the element kind: a
!> triangle of a tetrahedral body (3D, udar_contact_kernels) or a segment of
!> a 2D body's boundary (udar_segment2), chosen by the face's node count
!> (size(xa, 2): 3 or 2). The results keep the 3D layout: a segment's area
!> coordinates and shares have a third entry 0, which the matching
!> (match_velocities, the joint solve) takes as a node of weight and share
!> 0 (issue 14's 2D contact; theory.md 14). What the faces beside a face
!> decide (the seams of a dented surface, sharp convex edges) is one
!> implementation for both kinds. Pure: no state, no I/O.
module udar_contact_faces
  use udar_kinds, only: rk
  use udar_vectors, only: cross, gather_columns
  use udar_contact_kernels, only: triangle_projection, master_shares, closest_on_triangle, tetrahedron_coordinates, &
                                  behind_not, behind_face, behind_seam
  use udar_segment2, only: segment_projection, segment_shares, closest_on_segment, triangle_coordinates
  use udar_contact_search, only: bucket_grid_t, grid_build, grid_cell
  implicit none
  private
  public :: face_projection, face_shares, closest_on_face, seam_contact, element_coordinates, face_behind_surface, &
            face_beside_sharp_edge, points_inside_elements

  !> of an edge's length: a fold flatter than this, or a node nearer a plane,
  !> is rounding
  real(rk), parameter :: flat = 1.0e-9_rk

contains

  !> Unit normal n (out of the master body), signed distance dist of xs
  !> (negative: behind) and the coordinates g of its projection on face xa.
  pure subroutine face_projection(xa, xs, n, dist, g)
    real(rk), intent(in) :: xa(:,:), xs(3)
    real(rk), intent(out) :: n(3), dist, g(3)
    if (size(xa, 2) == 3) then
      call triangle_projection(xa, xs, n, dist, g)
    else
      call segment_projection(xa(:,1:2), xs, n, dist, g(1:2))
      g(3) = 0.0_rk
    end if
  end subroutine

  !> The face nodes' shares of a correction at xs (master_shares, segment_shares).
  pure subroutine face_shares(weights, xa, xs, g, n, xa0, xs0, r_share)
    integer, intent(in) :: weights
    real(rk), intent(in) :: xa(:,:), xs(3), g(3), n(3), xa0(:,:), xs0(3)
    real(rk), intent(out) :: r_share(3)
    if (size(xa, 2) == 3) then
      call master_shares(weights, xa, xs, g, n, xa0, xs0, r_share)
    else
      call segment_shares(weights, xa(:,1:2), xs, g(1:2), n, xa0(:,1:2), xs0, r_share(1:2))
      r_share(3) = 0.0_rk
    end if
  end subroutine

  !> The point c of face xa nearest to p and its coordinates g.
  pure subroutine closest_on_face(xa, p, c, g)
    real(rk), intent(in) :: xa(:,:), p(3)
    real(rk), intent(out) :: c(3), g(3)
    if (size(xa, 2) == 3) then
      call closest_on_triangle(xa, p, c, g)
    else
      call closest_on_segment(xa(:,1:2), p, c, g(1:2))
      g(3) = 0.0_rk
    end if
  end subroutine

  !> The contact of node xs in the seam of a dented surface beyond face xa's
  !> outline (face_behind_surface's behind_seam): with the face's closest
  !> point c (coordinates g), at depth dist < 0 along the unit direction n
  !> from the node to it (out of the body). taken: xs is not on the face,
  !> and, for a node on a symmetry plane (on_plane), the way to c is no
  !> longer than depth_limit: the symmetry condition keeps only the in-plane
  !> part of a move, so a node beyond the edge of a face leaning out of the
  !> plane, sent towards a closest point off the plane, was carried across
  !> the master body and left inside it (theory.md 11).
  pure subroutine seam_contact(xa, xs, depth_limit, on_plane, c, g, n, dist, taken)
    real(rk), intent(in) :: xa(:,:), xs(3), depth_limit
    logical, intent(in) :: on_plane
    real(rk), intent(out) :: c(3), g(3), n(3), dist
    logical, intent(out) :: taken
    call closest_on_face(xa, xs, c, g)
    dist = -norm2(c - xs)
    n = 0.0_rk
    taken = dist < 0.0_rk
    if (on_plane) taken = taken .and. dist >= -depth_limit
    if (taken) n = (xs - c)/dist
  end subroutine

  !> The coordinates lam of p in the master element made of face xa and its
  !> opposite corner xd (a tetrahedron: lam(1:4); a 2D triangle: lam(1:3),
  !> lam(4) = 0): p inside the element when all are >= 0.
  pure subroutine element_coordinates(xa, xd, p, lam)
    real(rk), intent(in) :: xa(:,:), xd(3), p(3)
    real(rk), intent(out) :: lam(4)
    real(rk) :: xt(3,3)
    if (size(xa, 2) == 3) then
      call tetrahedron_coordinates(xa, xd, p, lam)
    else
      xt(:,1:2) = xa(:,1:2)
      xt(:,3) = xd
      call triangle_coordinates(xt, p, lam(1:3))
      lam(4) = 0.0_rk
    end if
  end subroutine

  !> Which points p(:,j) lie in one of the elements elems (corners
  !> conn(e,:), of size(conn, 2) = 4 tetrahedra or 3 triangles, at x), to
  !> rounding of the area coordinates (on a face counts): the initial
  !> overlaps, and particles made inside a master body. An element with
  !> exclude(j) among its corners does not count for point j (a slave node
  !> is not inside its own elements). Only the elements reaching the
  !> points' box are binned (a grid over their boxes).
  pure subroutine points_inside_elements(conn, x, elems, p, inside, exclude)
    integer, intent(in) :: conn(:,:), elems(:)
    real(rk), intent(in) :: x(:,:), p(:,:)
    logical, intent(out) :: inside(:)
    integer, intent(in), optional :: exclude(:)
    real(rk), parameter :: rounding = 1.0e-9_rk
    integer, allocatable :: near(:)
    real(rk), allocatable :: lo(:,:), hi(:,:)
    type(bucket_grid_t) :: grid
    real(rk) :: xt(3,4), lam(4), p_lo(3), p_hi(3), e_lo(3), e_hi(3)
    integer :: j, e, k, c, s, nc, n_near, corner
    nc = size(conn, 2)
    inside = .false.
    if (size(p, 2) == 0 .or. size(elems) == 0) return
    p_lo = minval(p, dim=2)
    p_hi = maxval(p, dim=2)
    allocate(near(size(elems)), lo(3, size(elems)), hi(3, size(elems)))
    n_near = 0
    ! (corners gathered and boxed by loops: this runs over every element of
    ! the master bodies whenever particles are made)
    do k = 1, size(elems)
      call gather_columns(xt, x, conn(elems(k),:))
      e_lo = xt(:,1)
      e_hi = xt(:,1)
      do corner = 2, nc
        e_lo = min(e_lo, xt(:,corner))
        e_hi = max(e_hi, xt(:,corner))
      end do
      if (any(e_hi < p_lo) .or. any(e_lo > p_hi)) cycle
      n_near = n_near + 1
      near(n_near) = elems(k)
      lo(:,n_near) = e_lo
      hi(:,n_near) = e_hi
    end do
    if (n_near == 0) return
    call grid_build(grid, lo(:,1:n_near), hi(:,1:n_near))
    do j = 1, size(p, 2)
      c = grid_cell(grid, p(:,j))
      if (c == 0) cycle
      do s = grid%start(c), grid%start(c+1) - 1
        k = grid%items(s)
        if (any(p(:,j) < lo(:,k)) .or. any(p(:,j) > hi(:,k))) cycle
        e = near(k)
        if (present(exclude)) then
          if (any(conn(e,:) == exclude(j))) cycle
        end if
        call gather_columns(xt, x, conn(e,:))
        call element_coordinates(xt(:,1:nc-1), xt(:,nc), p(:,j), lam)
        if (minval(lam(1:nc)) < -rounding) cycle
        inside(j) = .true.
        exit
      end do
    end do
  end subroutine

  !> Where a node xs behind the plane (line) of master face xa (its
  !> face_projection: normal n, distance dist < 0, coordinates g) is, when
  !> its projection falls outside the face: across each edge (a segment's
  !> end) it falls beyond, the face there (xb(:,1:nf,a): the corners of the
  !> one across the edge (end) opposite corner a, counter-clockwise seen
  !> from outside; has(a) false: none known) decides.
  !> - Beyond a convex or flat edge (the neighbour's centre not in front of
  !>   this plane beyond rounding) the neighbour has the node, if anyone:
  !>   behind_not.
  !> - Beyond a concave edge (a dented surface) the body is behind either
  !>   plane: a node behind the neighbour's plane too whose projection falls
  !>   into the gap between the two outlines (within its depth times tan of
  !>   half the angle between the normals beyond the edge) is behind the
  !>   surface though on neither face (the seam a node slips through when a
  !>   step's approach is deep): behind_seam.
  !> - Without a neighbour (a rim) it is not behind this face.
  !> A projection on the face (no coordinate below -tol) is behind_face.
  pure integer function face_behind_surface(xa, n, dist, g, xb, has, xs, tol) result(verdict)
    real(rk), intent(in) :: xa(:,:), n(3), dist, g(3), xb(:,:,:), xs(3), tol
    logical, intent(in) :: has(:)
    real(rk) :: area2, edge, beyond, nb(3), db, gb(3), centre(3), cos_n
    integer :: a, nf
    verdict = behind_not
    nf = size(xa, 2)
    area2 = 0
    if (nf == 3) area2 = norm2(cross(xa(:,2) - xa(:,1), xa(:,3) - xa(:,1)))
    beyond = 0
    do a = 1, nf
      if (g(a) >= -tol) cycle
      if (.not. has(a)) return
      if (nf == 3) then
        edge = norm2(xa(:,mod(a+1,3)+1) - xa(:,mod(a,3)+1))
      else
        edge = norm2(xa(:,2) - xa(:,1))
      end if
      centre = sum(xb(:,1:nf,a), dim=2)/real(nf, rk)
      if (dot_product(n, centre - xa(:,1)) <= flat*edge) return
      call face_projection(xb(:,1:nf,a), xs, nb, db, gb)
      if (db > -flat*edge) return
      ! how far beyond the edge (end) the projection falls (a triangle's
      ! area2/edge: its altitude over the edge; a segment's length)
      if (nf == 3) then
        beyond = -g(a)*area2/edge
      else
        beyond = -g(a)*edge
      end if
      cos_n = dot_product(n, nb)
      if (beyond > -dist*sqrt(max(1.0_rk - cos_n, 0.0_rk)/(1.0_rk + cos_n))) return
      verdict = behind_seam
    end do
    if (verdict == behind_not) verdict = behind_face
  end function

  !> Whether a node xs behind the plane (line) of master face xa (normal n,
  !> coordinates g of its projection) is outside the body beside a sharp
  !> convex edge or corner of the face: on or in front of the plane of a
  !> face beside it (xb(:,1:nf,k), k = 1..nb, sharing the corners of xa
  !> marked in shares(:,k): an edge or a corner, a segment's node) that
  !> falls away behind this plane (its centre behind it), with its
  !> projection on that face (no coordinate below -tol) and on this one
  !> clear of what they share (the coordinates of the corners not shared
  !> sum to more than tol). Where two faces meet at an interior angle below
  !> 90 degrees (a fractured fragment's corner, a crater lip, a wedge's
  !> edge), a node on or just outside one of them is behind the other's
  !> plane with its projection on it, though it never crossed it. At 90
  !> degrees and more such a node projects onto the shared edge or corner
  !> or beyond it: a node at a body's square edge that crossed the top face
  !> stays the top face's.
  !> With the faces across the edges (segment ends) of each face beside
  !> (xc(:,1:nf,a,k): across the edge opposite its corner a; hasc(a,k)
  !> false: none known), a node in front of a face beside whose projection
  !> falls beyond some of its edges is outside too when each such edge is
  !> convex (the face across falls away behind the face beside) or the
  !> node is in front of the face across as well: near a convex edge the
  !> body is behind both planes. This is a thin fragment's knife edge, where
  !> a node outside the face beside projects just past that face's far edge.
  pure logical function face_beside_sharp_edge(xa, n, g, xb, shares, nb, xs, tol, xc, hasc) result(outside)
    integer, intent(in) :: nb
    real(rk), intent(in) :: xa(:,:), n(3), g(3), xb(:,:,:), xs(3), tol
    logical, intent(in) :: shares(:,:)
    real(rk), intent(in), optional :: xc(:,:,:,:)
    logical, intent(in), optional :: hasc(:,:)
    real(rk) :: longest, centre(3), nk(3), dk, gk(3)
    integer :: k, nf
    outside = .false.
    nf = size(xa, 2)
    if (nf == 3) then
      longest = max(norm2(xa(:,2) - xa(:,1)), norm2(xa(:,3) - xa(:,2)), norm2(xa(:,1) - xa(:,3)))
    else
      longest = norm2(xa(:,2) - xa(:,1))
    end if
    do k = 1, nb
      if (sum(g(1:nf), mask=.not. shares(1:nf,k)) <= tol) cycle
      centre = sum(xb(:,1:nf,k), dim=2)/real(nf, rk)
      if (dot_product(n, centre - xa(:,1)) >= -flat*longest) cycle     ! rising or flat
      call face_projection(xb(:,1:nf,k), xs, nk, dk, gk)
      if (dk <= -flat*longest) cycle
      if (any(gk(1:nf) < -tol)) then
        if (.not. present(xc)) cycle
        if (.not. beyond_convex_edges(xb(:,1:nf,k), nk, gk, xc(:,:,:,k), hasc(:,k))) cycle
      end if
      outside = .true.
      return
    end do

  contains

    !> Whether each edge of face xk (normal nk) that xs projects beyond
    !> (coordinates gk) is convex or has xs in front of the face across it.
    pure logical function beyond_convex_edges(xk, nk, gk, xc, hasc) result(ok)
      real(rk), intent(in) :: xk(:,:), nk(3), gk(3), xc(:,:,:)
      logical, intent(in) :: hasc(:)
      real(rk) :: nc(3), dc, gc(3), longest_k, middle(3)
      integer :: a
      ok = .false.
      longest_k = maxval([(norm2(xk(:,a) - xk(:,mod(a,nf)+1)), a = 1, nf)])
      do a = 1, nf
        if (gk(a) >= -tol) cycle
        if (.not. hasc(a)) return
        middle = sum(xc(:,1:nf,a), dim=2)/real(nf, rk)
        if (dot_product(nk, middle - xk(:,1)) < -flat*longest_k) cycle     ! falls away: convex
        call face_projection(xc(:,1:nf,a), xs, nc, dc, gc)
        if (dc <= -flat*longest_k) return
      end do
      ok = .true.
    end function
  end function
end module udar_contact_faces
