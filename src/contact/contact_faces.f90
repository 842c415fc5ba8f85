!> The contact geometry of a master face, whatever the element kind: a
!> triangle of a tetrahedral body (3D, udar_contact_kernels) or a segment of
!> a 2D body's boundary (udar_segment2), chosen by the face's node count
!> (size(xa, 2): 3 or 2). The results keep the 3D layout: a segment's area
!> coordinates and shares have a third entry 0, which the matching
!> (match_velocities, the joint solve) takes as a node of weight and share
!> 0 (issue 14's 2D contact; theory.md 14). Pure: no state, no I/O.
module udar_contact_faces
  use udar_kinds, only: rk
  use udar_contact_kernels, only: triangle_projection, master_shares, closest_on_triangle, tetrahedron_coordinates, &
                                  behind_surface, beside_sharp_edge
  use udar_segment2, only: segment_projection, segment_shares, closest_on_segment, triangle_coordinates, &
                           segment_behind_surface, segment_beside_corner
  implicit none
  private
  public :: face_projection, face_shares, closest_on_face, element_coordinates, face_behind_surface, &
            face_beside_sharp_edge

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

  !> Where a node xs behind face xa's plane or line is when its projection
  !> falls beyond the face (behind_surface, segment_behind_surface); xb, has:
  !> the faces across the face's edges (3D) or ends (2D), by opposite corner.
  pure integer function face_behind_surface(xa, n, dist, g, xb, has, xs, tol) result(verdict)
    real(rk), intent(in) :: xa(:,:), n(3), dist, g(3), xb(:,:,:), xs(3), tol
    logical, intent(in) :: has(:)
    real(rk) :: xb2(3,2,2)
    if (size(xa, 2) == 3) then
      verdict = behind_surface(xa, n, dist, g, xb, has, xs, tol)
    else
      xb2 = xb(:,1:2,1:2)      ! contiguous (a segment's slots of the 3D layout)
      verdict = segment_behind_surface(xa(:,1:2), n, dist, g(1:2), xb2, has(1:2), xs, tol)
    end if
  end function

  !> Whether a node xs behind face xa is outside the body beside a sharp
  !> convex edge or corner (beside_sharp_edge, segment_beside_corner): the
  !> nb faces xb beside it sharing the corners marked in shares.
  pure logical function face_beside_sharp_edge(xa, n, g, xb, shares, nb, xs, tol) result(outside)
    integer, intent(in) :: nb
    real(rk), intent(in) :: xa(:,:), n(3), g(3), xb(:,:,:), xs(3), tol
    logical, intent(in) :: shares(:,:)
    real(rk) :: xb2(3,2,3)
    logical :: shares2(2,3)
    if (size(xa, 2) == 3) then
      outside = beside_sharp_edge(xa, n, g, xb, shares, nb, xs, tol)
    else
      ! contiguous (a segment's slots of the 3D layout)
      xb2(:,:,1:nb) = xb(:,1:2,1:nb)
      shares2(:,1:nb) = shares(1:2,1:nb)
      outside = segment_beside_corner(xa(:,1:2), n, g(1:2), xb2(:,:,1:nb), shares2(:,1:nb), nb, xs, tol)
    end if
  end function
end module udar_contact_faces
