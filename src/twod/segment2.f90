!> The seed paper's contact geometry in 2D (issue 14): a slave node against a master segment of the boundary, in the
!> plane z = 0 (axisymmetric: x = r, y the axis; plane strain: x, y). The
!> paper states its algorithm unchanged for plane and axisymmetric
!> problems; in 2D its eqs. 1-5 are the signed distance of the node from the
!> segment's line, eqs. 6-12's shares are the linear interpolation along the
!> segment (R_i r_i = R_j r_j with r_i + r_j the segment's length), and the
!> velocity matching (eqs. 13-23) is the 3D kernel's with two master nodes
!> (udar_contact_kernels match_velocities: a third master node of weight 0
!> and share 0 takes no part). Points are 3-vectors with z = 0, as the
!> contact's node arrays hold them. Pure kernels: no state, no I/O.
module udar_segment2
  use udar_kinds, only: rk
  use udar_config, only: contact_weights_distance
  implicit none
  private
  public :: segment_projection, segment_shares, triangle_coordinates, closest_on_segment

contains

  !> Unit normal n of master segment (xa(:,1), xa(:,2)) (its two nodes in the
  !> counter-clockwise order of the master element's boundary: n = (dy, -dx)/L
  !> points out of the master body), signed distance dist of xs from its
  !> line (negative = behind the surface) and the linear coordinates g of
  !> the projection of xs onto the line (g(1) + g(2) = 1; both in [0, 1] on
  !> the segment).
  pure subroutine segment_projection(xa, xs, n, dist, g)
    real(rk), intent(in) :: xa(3,2), xs(3)
    real(rk), intent(out) :: n(3), dist, g(2)
    real(rk) :: e(2), len2, t
    e = xa(1:2,2) - xa(1:2,1)
    len2 = e(1)**2 + e(2)**2
    n = [e(2), -e(1), 0.0_rk]/sqrt(len2)
    dist = dot_product(n(1:2), xs(1:2) - xa(1:2,1))
    t = dot_product(e, xs(1:2) - xa(1:2,1))/len2
    g = [1.0_rk - t, t]
  end subroutine

  !> The master nodes' shares of a correction at the slave node xs (its
  !> projection g along normal n on segment xa), as master_shares in 3D:
  !> 'distance' (eq. 12: R_a inversely proportional to the distance r_a of
  !> xs from node a; the node at xs takes all), or 'area' (the shares at
  !> which the correction's line through the slave node's start position
  !> xs0 along n meets the segment at its start xa0: then it exerts no
  !> moment about the start positions, which keeps the leapfrog's angular
  !> momentum exact, theory.md 11; where the segment turned so far that its
  !> start line is within 60 degrees of containing n, g). On the segment and
  !> without motion both are the linear interpolation g.
  pure subroutine segment_shares(weights, xa, xs, g, n, xa0, xs0, r_share)
    integer, intent(in) :: weights
    real(rk), intent(in) :: xa(3,2), xs(3), g(2), n(3), xa0(3,2), xs0(3)
    real(rk), intent(out) :: r_share(2)
    real(rk) :: r(2), e(2), d(2), det
    if (weights == contact_weights_distance) then
      r(1) = norm2(xs(1:2) - xa(1:2,1))
      r(2) = norm2(xs(1:2) - xa(1:2,2))
      if (any(r == 0.0_rk)) then
        r_share = merge(1.0_rk, 0.0_rk, r == 0.0_rk)
        r_share = r_share/sum(r_share)
      else
        ! R_a = (1/r_a) / (1/r_1 + 1/r_2) = r_b / (r_1 + r_2)
        r_share = [r(2), r(1)]/(r(1) + r(2))
      end if
    else
      ! xa0_1 + t e = xs0 + alpha n: t = ((xs0 - xa0_1) x n)/(e x n)
      e = xa0(1:2,2) - xa0(1:2,1)
      d = xs0(1:2) - xa0(1:2,1)
      det = e(1)*n(2) - e(2)*n(1)
      if (abs(det) < 0.5_rk*norm2(e)) then
        r_share = g
      else
        r_share(2) = (d(1)*n(2) - d(2)*n(1))/det
        r_share(1) = 1.0_rk - r_share(2)
      end if
    end if
  end subroutine

  !> The point c of segment xa nearest to p (the 2D closest_on_triangle:
  !> where a node behind the surface beyond a corner meets it) and its
  !> linear coordinates g (both in [0, 1]).
  pure subroutine closest_on_segment(xa, p, c, g)
    real(rk), intent(in) :: xa(3,2), p(3)
    real(rk), intent(out) :: c(3), g(2)
    real(rk) :: e(3), t
    e = xa(:,2) - xa(:,1)
    t = min(max(dot_product(e, p - xa(:,1))/dot_product(e, e), 0.0_rk), 1.0_rk)
    g = [1.0_rk - t, t]
    c = xa(:,1) + t*e
  end subroutine

  !> Area coordinates lam of point p in triangle xa (corners xa(:,a), in the
  !> plane z = 0): p inside when all three are >= 0 (the 2D counterpart of
  !> tetrahedron_coordinates: a slave node inside a master element however
  !> deep). A degenerate triangle gives lam = -1 (outside).
  pure subroutine triangle_coordinates(xa, p, lam)
    real(rk), intent(in) :: xa(3,3), p(3)
    real(rk), intent(out) :: lam(3)
    real(rk) :: area2
    area2 = (xa(1,2) - xa(1,1))*(xa(2,3) - xa(2,1)) - (xa(1,3) - xa(1,1))*(xa(2,2) - xa(2,1))
    if (area2 == 0.0_rk) then
      lam = -1.0_rk
      return
    end if
    lam(1) = ((xa(1,2) - p(1))*(xa(2,3) - p(2)) - (xa(1,3) - p(1))*(xa(2,2) - p(2)))/area2
    lam(2) = ((xa(1,3) - p(1))*(xa(2,1) - p(2)) - (xa(1,1) - p(1))*(xa(2,3) - p(2)))/area2
    lam(3) = 1.0_rk - lam(1) - lam(2)
  end subroutine

end module udar_segment2
