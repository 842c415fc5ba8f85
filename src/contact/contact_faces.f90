!> The contact geometry of a master face, whatever the element kind: a
!> triangle of a tetrahedral body (3D, udar_contact_kernels) or a segment of
!> a 2D body's boundary (udar_segment2), chosen by the face's node count
!> (size(xa, 2): 3 or 2). The results keep the 3D layout: a segment's area
!> coordinates and shares have a third entry 0, which the matching
!> (match_velocities, the joint solve) takes as a node of weight and share
!> 0 (issue 14's 2D contact; theory.md 14). Pure: no state, no I/O.
module udar_contact_faces
  use udar_kinds, only: rk
  use udar_contact_kernels, only: triangle_projection, master_shares, closest_on_triangle, tetrahedron_coordinates
  use udar_segment2, only: segment_projection, segment_shares, closest_on_segment, triangle_coordinates
  implicit none
  private
  public :: face_projection, face_shares, closest_on_face, element_coordinates

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
end module udar_contact_faces
