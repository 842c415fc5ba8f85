!> The seed paper's contact correction for one slave node against one
!> master triangle (Yugov, Belov, Khabibullin, Starenchenko 1998, eqs. 1-23,
!> with the corrections of doc/theory.md). Pure kernels: no state, no I/O.
module udar_contact_kernels
  use udar_kinds, only: rk
  use udar_config, only: contact_weights_distance
  use udar_vectors, only: cross
  implicit none
  private
  public :: triangle_projection, master_shares, match_velocities, tetrahedron_coordinates, solve_friction_rows, row_components, edge_crossing, edge_shares, &
            closest_on_triangle, behind_not, behind_face, behind_seam, &
            solve_normal_lcp, normal_rows_matrix, contact_point, corner_angle, &
            constrained_projection, return_on_planes

  !> The least share of a row's normal that the symmetry planes must let
  !> its nodes move along (n . K n over the unconstrained denominator,
  !> match_velocities with proj) for the row to be matched again along the
  !> planes: below it (a face within 30 degrees of lying in the plane) the
  !> match would send the node along the plane at more than twice its
  !> approach, which a face nearly in the plane and its mirror image do
  !> not do to the material between them (regression/oblique_particles: a
  !> particle at 3.4 times the impact speed with 1e-12), and the row is
  !> left as the first matching and the velocity conditions leave it.
  real(rk), parameter :: plane_lean_limit = 0.25_rk

  !> udar_contact_faces' face_behind_surface's verdicts: not behind the
  !> surface; behind this face; behind the surface beyond one of its concave
  !> edges (the contact point is then the face's closest point)
  integer, parameter :: behind_not = 0, behind_face = 1, behind_seam = 2

contains

  !> Unit normal n of triangle (xa(:,1), xa(:,2), xa(:,3)) (counter-clockwise
  !> seen from outside the master body: n points out of it), signed distance
  !> of xs from its plane (eq. 4; negative = behind the surface), and the area
  !> coordinates g of the projection of xs onto the plane (eqs. 14-15 in
  !> the triangle's own plane, valid for any orientation).
  pure subroutine triangle_projection(xa, xs, n, dist, g)
    real(rk), intent(in) :: xa(3,3), xs(3)
    real(rk), intent(out) :: n(3), dist, g(3)
    real(rk) :: e1(3), e2(3), c(3), area2, p(3)
    e1 = xa(:,2) - xa(:,1)
    e2 = xa(:,3) - xa(:,1)
    c = cross(e1, e2)                   ! (A, B, C) of eq. 2
    area2 = norm2(c)
    n = c/area2
    dist = dot_product(n, xs - xa(:,1))
    p = xs - dist*n
    ! sub-triangle areas opposite each vertex, signed by the normal
    g(1) = dot_product(n, cross(xa(:,2) - p, xa(:,3) - p))/area2
    g(2) = dot_product(n, cross(xa(:,3) - p, xa(:,1) - p))/area2
    g(3) = 1.0_rk - g(1) - g(2)
  end subroutine

  !> The point c of triangle xa closest to p, and its area coordinates g
  !> (all in [0, 1]): the projection if it falls on the triangle, else
  !> the closest point of the nearest edge or corner.
  pure subroutine closest_on_triangle(xa, p, c, g)
    real(rk), intent(in) :: xa(3,3), p(3)
    real(rk), intent(out) :: c(3), g(3)
    real(rk) :: n(3), dist, s, best, e(3), q(3), d2
    integer :: a, i, j
    call triangle_projection(xa, p, n, dist, g)
    if (all(g >= 0.0_rk)) then
      c = p - dist*n
      return
    end if
    best = huge(1.0_rk)
    do a = 1, 3
      ! the edge opposite corner a, from corner i to corner j
      i = mod(a,3) + 1
      j = mod(a+1,3) + 1
      e = xa(:,j) - xa(:,i)
      s = min(max(dot_product(p - xa(:,i), e)/max(dot_product(e, e), tiny(1.0_rk)), 0.0_rk), 1.0_rk)
      q = xa(:,i) + s*e
      d2 = sum((p - q)**2)
      if (d2 < best) then
        best = d2
        c = q
        g = 0
        g(i) = 1.0_rk - s
        g(j) = s
      end if
    end do
  end subroutine

  !> The angle (rad) of triangle xa at its corner a: the weight of its
  !> normal in the angle-weighted normal of a vertex, whose side tells
  !> inside from outside a closed surface for a point whose nearest surface
  !> point is that vertex (Baerentzen and Aanaes 2005).
  pure real(rk) function corner_angle(xa, a) result(angle)
    real(rk), intent(in) :: xa(3,3)
    integer, intent(in) :: a
    real(rk) :: e1(3), e2(3)
    e1 = xa(:,mod(a,3)+1) - xa(:,a)
    e2 = xa(:,mod(a+1,3)+1) - xa(:,a)
    ! atan2 of |e1 x e2| and e1.e2: accurate at small and large angles alike
    angle = atan2(norm2(cross(e1, e2)), dot_product(e1, e2))
  end function

  !> Barycentric coordinates lam of point p in the tetrahedron of master
  !> triangle xa and its fourth corner xd (the element under the face):
  !> p is inside when every lam >= 0; lam(4) is its depth behind the face
  !> over the corner's.
  pure subroutine tetrahedron_coordinates(xa, xd, p, lam)
    real(rk), intent(in) :: xa(3,3), xd(3), p(3)
    real(rk), intent(out) :: lam(4)
    real(rk) :: v
    v = six_volume(xa(:,1), xa(:,2), xa(:,3), xd)
    lam(1) = six_volume(p, xa(:,2), xa(:,3), xd)/v
    lam(2) = six_volume(xa(:,1), p, xa(:,3), xd)/v
    lam(3) = six_volume(xa(:,1), xa(:,2), p, xd)/v
    lam(4) = 1.0_rk - lam(1) - lam(2) - lam(3)
  end subroutine

  pure real(rk) function six_volume(a, b, c, d)
    real(rk), intent(in) :: a(3), b(3), c(3), d(3)
    six_volume = dot_product(b - a, cross(c - a, d - a))
  end function

  !> Shares R of the slave node's momentum for the three master nodes
  !> (sum R = 1): inversely proportional to the distances r_a = |xs - x_a|
  !> (weights = distance: eqs. 6-12, R_i = 1/(1 + r_i/r_j + r_i/r_k), a node
  !> at r = 0 takes all), or (weights = area) the area coordinates of the
  !> slave node's position at the start of the step, xs0, projected along
  !> the contact normal n onto the triangle's plane at the start, xa0. The
  !> correction then exerts no moment about the start positions, which is
  !> what keeps the leapfrog's angular momentum sum m x(n) x v(n+1/2)
  !> exact (theory.md 11); with xs0 = xs, xa0 = xa (no motion) they are the
  !> area coordinates g of the projection. Where the triangle turned so far
  !> over the step that its start plane is within 60 degrees of containing n,
  !> g.
  pure subroutine master_shares(weights, xa, xs, g, n, xa0, xs0, r_share)
    integer, intent(in) :: weights
    real(rk), intent(in) :: xa(3,3), xs(3), g(3), n(3), xa0(3,3), xs0(3)
    real(rk), intent(out) :: r_share(3)
    real(rk) :: r(3), e1(3), e2(3), c(3), det
    integer :: a
    if (weights == contact_weights_distance) then
      do a = 1, 3
        r(a) = norm2(xs - xa(:,a))
      end do
      if (any(r == 0.0_rk)) then
        r_share = merge(1.0_rk, 0.0_rk, r == 0.0_rk)
        r_share = r_share/sum(r_share)
      else
        ! R_a = (1/r_a) / sum(1/r_b): the same as eq. 12, without divisions by small r
        r_share = [r(2)*r(3), r(1)*r(3), r(1)*r(2)]
        r_share = r_share/sum(r_share)
      end if
    else
      ! xs0 - sum_a R_a xa0 = alpha n with R_3 = 1 - R_1 - R_2 (Cramer's rule)
      e1 = xa0(:,1) - xa0(:,3)
      e2 = xa0(:,2) - xa0(:,3)
      r = xs0 - xa0(:,3)
      c = cross(e2, n)
      det = dot_product(e1, c)
      if (abs(det) < 0.5_rk*norm2(cross(e1, e2))) then
        r_share = g
      else
        r_share(1) = dot_product(r, c)/det
        r_share(2) = dot_product(e1, cross(r, n))/det
        r_share(3) = 1.0_rk - r_share(1) - r_share(2)
      end if
    end if
  end subroutine

  !> Velocity matching (eqs. 13, 16-18) and algorithmic friction (eqs.
  !> 19-23, with the stick limit) of slave node s (mass ms, velocity vs)
  !> against the master triangle's nodes (masses mm, velocities vm(:,a)) at
  !> area coordinates g with shares r_share, along the unit normal n.
  !> One pass of the iterations (projected Gauss-Seidel): dn_before and
  !> t_before are the normal and tangential velocity changes this node has
  !> received so far in this cycle. The change made now matches the normal
  !> velocities and stops the slip, then is clamped so that the accumulated
  !> changes stay admissible: the normal one compressive (dn >= -dn_before:
  !> an earlier push that later corrections made too large is taken back),
  !> the tangential one within friction times the normal one (Coulomb). So
  !> the iterations converge to one answer whatever order the nodes come in.
  !> A node that has received nothing and moves away from the surface is
  !> left alone (separation). Momentum is conserved: ms dvs + sum_a mm(a)
  !> dvm(:,a) = 0. Returns the velocity changes, whether anything changed
  !> (acted), and this pass's normal change dn (signed) and tangential
  !> change dtv of the slave node. With normal_held (a joint pass's
  !> friction sweeps, whose normal changes the joint solve sets) the normal
  !> change is 0 and only a node that has received a normal change gets
  !> friction.
  !> With proj (a row with a node on a symmetry plane, matched again as the
  !> planes let its nodes move: proj(:,:,0) the slave's projection,
  !> proj(:,:,a) master node a's, constrained_projection) the change is
  !> the normal one alone, friction not taken: the impulse per slave mass
  !> dn n moves the slave by dvs = dn P_s n and master node a by dvm(:,a) =
  !> -dn (R_a ms/m_a) P_a n, so the normal velocities are equal afterwards
  !> for dn = n . v_rel / (n . K n), K = P_s + sum_a g_a R_a (ms/m_a) P_a
  !> (K = denom I off the planes). A row whose normal the nodes may hardly
  !> move along (n . K n below plane_lean_limit of denom) does nothing.
  pure subroutine match_velocities(n, ms, vs, mm, vm, g, r_share, friction, dn_before, t_before, dvs, dvm, &
                                   acted, dn, dtv, normal_held, proj)
    real(rk), intent(in) :: n(3), ms, vs(3), mm(3), vm(3,3), g(3), r_share(3), friction, dn_before, t_before(3)
    real(rk), intent(out) :: dvs(3), dvm(3,3), dn, dtv(3)
    logical, intent(out) :: acted
    logical, intent(in), optional :: normal_held
    real(rk), intent(in), optional :: proj(3,3,0:3)
    real(rk) :: v_master(3), denom, vr(3), t_new(3), t_mag, limit, gc(3), kn(3)
    integer :: a
    dvs = 0.0_rk
    dvm = 0.0_rk
    dn = 0.0_rk
    dtv = 0.0_rk
    acted = .false.
    gc = contact_point(g)
    v_master = gc(1)*vm(:,1) + gc(2)*vm(:,2) + gc(3)*vm(:,3)
    ! eq. 17: the denominator that makes the normal velocities equal afterwards
    denom = 1.0_rk + ms*(gc(1)*r_share(1)/mm(1) + gc(2)*r_share(2)/mm(2) + gc(3)*r_share(3)/mm(3))
    if (present(proj)) then
      kn = matmul(proj(:,:,0), n)
      do a = 1, 3
        kn = kn + (gc(a)*r_share(a)*ms/mm(a))*matmul(proj(:,:,a), n)
      end do
      if (dot_product(n, kn) < plane_lean_limit*denom) return
      dn = dot_product(n, v_master - vs)/dot_product(n, kn)
    else
      dn = dot_product(n, v_master - vs)/denom
    end if
    if (present(normal_held)) then
      if (normal_held) dn = 0.0_rk
    end if
    if (dn <= 0.0_rk .and. dn_before <= 0.0_rk) then
      dn = 0.0_rk                          ! separating: released
      return
    end if
    dn = max(dn, -dn_before)
    if (present(proj)) then
      dvs = dn*matmul(proj(:,:,0), n)
      do a = 1, 3
        dvm(:,a) = -(dn*r_share(a)*ms/mm(a))*matmul(proj(:,:,a), n)
      end do
      acted = dn /= 0.0_rk
      return
    end if
    ! friction: the change that stops the relative tangential velocity (the
    ! normal change leaves it as it is; the same denominator), the accumulated
    ! tangential change limited to friction times the accumulated normal one
    if (friction > 0.0_rk) then
      vr = v_master - vs
      vr = vr - dot_product(vr, n)*n
      t_new = t_before + vr/denom
      limit = friction*(dn_before + dn)
      t_mag = norm2(t_new)
      if (t_mag > limit) t_new = (limit/t_mag)*t_new
      dtv = t_new - t_before
    end if
    dvs = dn*n + dtv
    do a = 1, 3
      dvm(:,a) = -(r_share(a)*ms/mm(a))*dvs
    end do
    acted = dn /= 0.0_rk .or. any(dtv /= 0.0_rk)
  end subroutine

  !> The projection onto the motions a node's symmetry planes allow: the
  !> identity less the outer products of the planes' normals (those of the
  !> set bits of bits among planes(1:3,:)), orthonormalised (a node on two
  !> planes moves along their line); the identity for bits = 0.
  pure function constrained_projection(bits, planes) result(p)
    integer, intent(in) :: bits
    real(rk), intent(in) :: planes(:,:)
    real(rk) :: p(3,3), e(3,3), d(3)
    integer :: k, i, j, ne
    p = 0.0_rk
    do i = 1, 3
      p(i,i) = 1.0_rk
    end do
    ne = 0
    do k = 1, size(planes, 2)
      if (.not. btest(bits, k - 1)) cycle
      d = planes(1:3,k)
      do j = 1, ne
        d = d - dot_product(d, e(:,j))*e(:,j)
      end do
      if (norm2(d) <= 1.0e-9_rk .or. ne == 3) cycle
      ne = ne + 1
      e(:,ne) = d/norm2(d)
      do j = 1, 3
        do i = 1, 3
          p(i,j) = p(i,j) - e(i,ne)*e(j,ne)
        end do
      end do
    end do
  end function

  !> A node's return u (to a face's plane or a closest point) for a node on
  !> symmetry planes (p its constrained_projection): along the part P u
  !> the planes allow, as far as takes it as far along u, (u . u)/(u . P u)
  !> P u (the velocity conditions would otherwise keep only P u, leaving
  !> it behind a face that leans out of the plane); 0 where the planes allow
  !> no motion along u (u . P u within 1e-12 of u . u: the mirror image
  !> holds that gap).
  pure function return_on_planes(u, p) result(w)
    real(rk), intent(in) :: u(3), p(3,3)
    real(rk) :: w(3), pu(3), c
    pu = matmul(p, u)
    c = dot_product(u, pu)
    w = 0.0_rk
    if (c > 1.0e-12_rk*dot_product(u, u)) w = (dot_product(u, u)/c)*pu
  end function

  !> The matrix of a pass's normal rows for solve_normal_lcp: row r is
  !> slave node node(0,r) against master nodes node(1:3,r) at weights
  !> w(1:3,r) (the contact point; w(0,r) = -1 for the slave), along unit
  !> normal nrm(:,r); a normal change lam_q of row q's slave node changes
  !> node p's velocity by coef(p,q) lam_q nrm(:,q) (1 for the slave, -R_a
  !> m_s/m_a for master node a), so row r's separation rate
  !> -nrm_r . (sum_a w_a v_a - v_s) changes by
  !>   m(r,q) = -(nrm_r . nrm_q) sum over the nodes shared by the rows of w(c,r) coef(p,q).
  !> With dirs, row q's change moves node p along dirs(:,p,q) (a node on a
  !> symmetry plane: nrm_q projected, constrained_projection), and m(r,q) =
  !> -sum of w(c,r) coef(p,q) (nrm_r . dirs(:,p,q)).
  pure subroutine normal_rows_matrix(n, ld, node, w, coef, nrm, m, dirs)
    integer, intent(in) :: n, ld, node(0:3,n)
    real(rk), intent(in) :: w(0:3,n), coef(0:3,n), nrm(3,n)
    real(rk), intent(inout) :: m(ld,ld)       !< m(1:n,1:n) set
    real(rk), intent(in), optional :: dirs(3,0:3,n)
    integer :: r, q, c, p
    do q = 1, n
      if (present(dirs)) then
        do r = 1, n
          m(r,q) = 0.0_rk
          do c = 0, 3
            do p = 0, 3
              if (node(c,r) == node(p,q)) m(r,q) = m(r,q) - w(c,r)*coef(p,q)*dot_product(nrm(:,r), dirs(:,p,q))
            end do
          end do
        end do
        cycle
      end if
      do r = 1, n
        m(r,q) = 0.0_rk
        do c = 0, 3
          do p = 0, 3
            if (node(c,r) == node(p,q)) m(r,q) = m(r,q) + w(c,r)*coef(p,q)
          end do
        end do
        m(r,q) = -dot_product(nrm(:,r), nrm(:,q))*m(r,q)
      end do
    end do
  end subroutine

  !> The normal rows of a contact pass solved together: lam >= 0 with
  !>   s = b + M lam >= 0,  lam_r s_r = 0  (a linear complementarity problem),
  !> M(r,q) the separation rate of row r per unit normal velocity change of
  !> row q's slave node, b the rows' separation rates before. The rows'
  !> own impulses are what projected Gauss-Seidel converges to; solved
  !> directly, rows that constrain one gap from both sides (a symmetric
  !> pair, self-contact) need no slow sweeps. Block principal pivoting
  !> (Judice and Pires 1994): guess the rows in contact (approaching
  !> ones), solve them as equalities, move rows with lam < 0 out and
  !> separating-rate violations in; ok = .false. after 3 n + 10 guesses
  !> (or max_guesses, if fewer: each costs a dense solve).
  !> Flipping every infeasible row at once can cycle (it did on a 321-row
  !> self-contact pass, and on 3-row positive definite problems), so if
  !> safeguarded, after safe_flips guesses that do not lower the count of
  !> infeasible rows below its best, a guess flips only the infeasible row
  !> of highest index (Murty's rule, finite for a positive definite M)
  !> until the count does fall (Judice and Pires' safeguard). On unless
  !> safeguarded = .false. (kept for the unit test that shows the cycle):
  !> it acts only after three guesses that do not improve, and the Fig. 4
  !> deck's history at dt_safety 0.37 is byte-identical with it (theory.md 11).
  !> M_AA regularised by 1e-10 of its largest diagonal (two rows on one gap
  !> make it singular: any split of their impulse serves), Gaussian
  !> elimination with partial pivoting. m, work and free: leading dimension
  !> ld >= n (the caller's fixed-size arrays; work and free are work).
  pure subroutine solve_normal_lcp(n, ld, m, b, lam, ok, work, free, safeguarded, max_guesses)
    integer, intent(in) :: n, ld
    logical, intent(in), optional :: safeguarded
    integer, intent(in), optional :: max_guesses
    real(rk), intent(in) :: m(ld,ld), b(n)
    real(rk), intent(out) :: lam(n)
    logical, intent(out) :: ok
    real(rk), intent(inout) :: work(ld,ld+1)
    logical, intent(inout) :: free(ld)
    integer, parameter :: safe_flips = 3
    real(rk) :: s(n), tol, reg, sol(n)
    integer :: it, r, q, na, i, j, n_bad, best, flips_left, guesses
    integer :: idx(n)
    logical :: bad(n), guard
    lam = 0.0_rk
    ok = .true.
    if (n == 0) return
    tol = 1.0e-12_rk*max(maxval(abs(b)), tiny(1.0_rk))
    reg = 1.0e-10_rk*maxval([(abs(m(r,r)), r = 1, n)])
    free(1:n) = b < 0.0_rk
    best = n + 1
    flips_left = safe_flips
    guard = .true.
    if (present(safeguarded)) guard = safeguarded
    guesses = 3*n + 10
    if (present(max_guesses)) guesses = min(guesses, max_guesses)
    do it = 1, guesses
      ! the rows guessed in contact, as equalities
      na = 0
      do r = 1, n
        if (.not. free(r)) cycle
        na = na + 1
        idx(na) = r
      end do
      lam = 0.0_rk
      if (na > 0) then
        do i = 1, na
          do j = 1, na
            work(i,j) = m(idx(i),idx(j))
          end do
          work(i,i) = work(i,i) + reg
          work(i,na+1) = -b(idx(i))
        end do
        call solve_dense(na, ld, work, sol, ok)
        if (.not. ok) return
        lam(idx(1:na)) = sol(1:na)
      end if
      s = b + matmul(m(1:n,1:n), lam)
      ! complementary within rounding: done (a NaN counts as infeasible)
      bad = merge(.not. lam >= 0.0_rk, .not. s >= -tol, free(1:n))
      n_bad = count(bad)
      if (n_bad == 0) exit
      if (it == guesses) then
        ok = .false.
        return
      end if
      if (n_bad < best) then
        best = n_bad
        flips_left = safe_flips
      else
        flips_left = flips_left - 1
      end if
      if (flips_left >= 0 .or. .not. guard) then
        do q = 1, n
          if (free(q)) then
            free(q) = lam(q) > 0.0_rk
          else
            free(q) = s(q) < -tol
          end if
        end do
      else
        q = findloc(bad, .true., dim=1, back=.true.)
        free(q) = .not. free(q)
      end if
    end do
    lam = max(lam, 0.0_rk)
  end subroutine

  !> The sets of rows joined by shared nodes (directly or through other
  !> rows): comp(r) in 1..n_comp, numbered in the order of their first
  !> rows. Rows of different sets do not change each other's rates, so
  !> each set can be solved on its own. Union-find through each node's
  !> first row (node_row, indexed by node: 0 on entry, left 0), so O(n).
  pure subroutine row_components(n, node, node_row, comp, n_comp)
    integer, intent(in) :: n, node(0:3,n)
    integer, intent(inout) :: node_row(:)
    integer, intent(out) :: comp(n), n_comp
    integer :: r, i, parent(n), relabel(n), root_r, root_q
    parent = [(r, r = 1, n)]
    do r = 1, n
      do i = 0, 3
        if (node_row(node(i,r)) == 0) then
          node_row(node(i,r)) = r
          cycle
        end if
        root_r = root(r)
        root_q = root(node_row(node(i,r)))
        if (root_r /= root_q) parent(max(root_r, root_q)) = min(root_r, root_q)
      end do
    end do
    do r = 1, n
      node_row(node(:,r)) = 0
    end do
    relabel = 0
    n_comp = 0
    do r = 1, n
      root_r = root(r)
      if (relabel(root_r) == 0) then
        n_comp = n_comp + 1
        relabel(root_r) = n_comp
      end if
      comp(r) = relabel(root_r)
    end do
  contains
    pure integer function root(j)
      integer, intent(in) :: j
      root = j
      do while (parent(root) /= root)
        root = parent(root)
      end do
    end function
  end subroutine

  !> a(1:n,1:n) x = a(1:n,n+1) by Gaussian elimination with partial
  !> pivoting (a is overwritten); ok = .false. at a zero pivot. The
  !> elimination runs down the columns (contiguous in memory: row by row
  !> it took 25 ms for 200 rows at a leading dimension of 512); each
  !> entry's update is the same either way.
  pure subroutine solve_dense(n, ld, a, x, ok)
    integer, intent(in) :: n, ld
    real(rk), intent(inout) :: a(ld,ld+1)
    real(rk), intent(out) :: x(n)
    logical, intent(out) :: ok
    real(rk) :: piv
    integer :: i, j, k, p
    ok = .false.
    do k = 1, n
      p = k - 1 + maxloc(abs(a(k:n,k)), dim=1)
      if (p /= k) a([k,p],k:n+1) = a([p,k],k:n+1)
      piv = a(k,k)
      if (piv == 0.0_rk) return
      ! the multipliers in the column they eliminate (not read again)
      a(k+1:n,k) = a(k+1:n,k)/piv
      do j = k + 1, n + 1
        do i = k + 1, n
          a(i,j) = a(i,j) - a(i,k)*a(k,j)
        end do
      end do
    end do
    do k = n, 1, -1
      x(k) = (a(k,n+1) - dot_product(a(k,k+1:n), x(k+1:n)))/a(k,k)
    end do
    ok = .true.
  end subroutine

  !> The rows of a contact pass with Coulomb friction solved together: the
  !> fixed point of match_velocities' sweeps. Contact q has unknowns
  !> x(3q-2) (its slave node's accumulated normal velocity change, >= 0)
  !> and x(3q-1:3q) (its accumulated tangential change in a tangent basis),
  !> rates s = b + M (x - x0) (s(3q-2) the separation rate, s(3q-1:3q) the
  !> slave's slip against its master point; b the rates at x0, M(i,j) the
  !> rate i per unit change j). The conditions, in Alart and Curnier's
  !> (1991) form with r = 1/M(3q-2,3q-2) (then 0.3 and 3 times it, if the
  !> first fails):
  !>   lam = max(0, lam - r s_n),  T = P(T - r u),
  !> P the projection on the disc of radius mu_q max(0, lam - r s_n)
  !> (stick: u = 0 inside it; slip: T = mu lam against u on its edge),
  !> solved by the semi-smooth Newton method (its generalised Jacobian)
  !> until every residual is within 1e-13 of the scale of b and x0.
  !> Rows that constrain one gap from both sides make M nearly singular
  !> where projected Gauss-Seidel converges only slowly; Newton's steps do
  !> not care. Each step is halved until the residual falls (a step's
  !> Jacobian holds only on its piece of the conditions), its diagonal
  !> shifted more after short steps; ok = .false. (x = x0) when no r
  !> converges in max_newton steps. jac: leading dimension ld >= 3 n (work).
  pure subroutine solve_friction_rows(n, ld, m, b, x0, mu, x, ok, jac)
    integer, intent(in) :: n, ld
    real(rk), intent(in) :: m(ld,ld), b(3*n), x0(3*n), mu(n)
    real(rk), intent(out) :: x(3*n)
    logical, intent(out) :: ok
    real(rk), intent(inout) :: jac(ld,ld+1)
    integer, parameter :: max_newton = 60, max_halvings = 20
    ! the scale of the conditions' augmentation (r of 1/M_ii times these):
    ! another changes where their pieces meet, so a start that stalls on
    ! one may not on the next
    real(rk), parameter :: r_factors(3) = [1.0_rk, 0.3_rk, 3.0_rk]
    real(rk) :: f(3*n), dx(3*n), x_try(3*n), f_try(3*n), tol, size_f, step, reg, shift, rf
    integer :: it, k, nn, attempt
    nn = 3*n
    x = x0
    ok = .true.
    if (n == 0) return
    tol = 1.0e-13_rk*max(maxval(abs(b)), maxval(abs(x0)), tiny(1.0_rk))
    do attempt = 1, size(r_factors)
      rf = r_factors(attempt)
      shift = 1.0e-10_rk
      x = x0
      call residual(x, f, .true., jac)
      do it = 1, max_newton
        size_f = norm2(f)
        if (maxval(abs(f)) <= tol) return
        jac(1:nn,nn+1) = -f
        ! two rows on one gap make the Jacobian singular where they stick
        ! (any split of their change serves): regularised, as in solve_normal_lcp
        reg = shift*maxval([(abs(jac(k,k)), k = 1, nn)])
        do k = 1, nn
          jac(k,k) = jac(k,k) + reg
        end do
        call solve_dense(nn, ld, jac, dx, ok)
        if (.not. ok) exit
        ! the full step, or halved until the residual falls (the conditions
        ! are only piecewise smooth: a full step can cycle between pieces)
        step = 1.0_rk
        do k = 1, max_halvings
          x_try = x + step*dx
          call residual(x_try, f_try, .false., jac)
          if (norm2(f_try) < (1.0_rk - 1.0e-4_rk*step)*size_f) exit
          step = 0.5_rk*step
        end do
        ! short steps: the next one leans towards the residual's own direction
        ! (a larger shift of the Jacobian's diagonal), full ones away from it
        if (step < 0.125_rk) then
          shift = min(100.0_rk*shift, 1.0_rk)
        else if (step >= 0.5_rk) then
          shift = max(0.1_rk*shift, 1.0e-10_rk)
        end if
        x = x_try
        call residual(x, f, .true., jac)
      end do
      if (maxval(abs(f)) <= tol) return
    end do
    x = x0
    ok = .false.
  contains
    !> The residuals at y and, if asked, their generalised Jacobian in jac.
    pure subroutine residual(y, fy, with_jac, jm)
      real(rk), intent(in) :: y(3*n)
      real(rk), intent(out) :: fy(3*n)
      logical, intent(in) :: with_jac
      real(rk), intent(inout) :: jm(ld,ld+1)
      real(rk) :: s(3*n), r, an, z(2), zm, lim, zh(2), dz(2), dl
      integer :: q, i, j
      s = b + matmul(m(1:nn,1:nn), y - x0)
      do q = 1, n
        i = 3*q - 2
        r = rf/m(i,i)
        an = y(i) - r*s(i)
        if (an > 0.0_rk) then
          fy(i) = r*s(i)                        ! in contact: closed
          if (with_jac) jm(i,1:nn) = r*m(i,1:nn)
        else
          fy(i) = y(i)                          ! released
          if (with_jac) then
            jm(i,1:nn) = 0.0_rk
            jm(i,i) = 1.0_rk
          end if
        end if
        lim = mu(q)*max(an, 0.0_rk)
        z = y(i+1:i+2) - r*s(i+1:i+2)
        zm = norm2(z)
        if (zm <= lim) then
          fy(i+1:i+2) = r*s(i+1:i+2)            ! sticking
          if (with_jac) jm(i+1:i+2,1:nn) = r*m(i+1:i+2,1:nn)
        else
          zh = z/zm                             ! sliding against the slip
          fy(i+1:i+2) = y(i+1:i+2) - lim*zh
          if (.not. with_jac) cycle
          do j = 1, nn
            dz = -r*m(i+1:i+2,j)
            if (j == i + 1) dz(1) = dz(1) + 1.0_rk
            if (j == i + 2) dz(2) = dz(2) + 1.0_rk
            dl = 0.0_rk
            if (an > 0.0_rk) dl = -mu(q)*r*m(i,j)
            if (an > 0.0_rk .and. j == i) dl = dl + mu(q)
            jm(i+1:i+2,j) = -(zh*dl + (lim/zm)*(dz - zh*dot_product(zh, dz)))
            if (j == i + 1) jm(i+1,j) = jm(i+1,j) + 1.0_rk
            if (j == i + 2) jm(i+2,j) = jm(i+2,j) + 1.0_rk
          end do
        end if
      end do
    end subroutine
  end subroutine

  !> The contact point's weights on the triangle's nodes: the area
  !> coordinates g of the projection, clipped into the triangle.
  pure function contact_point(g) result(gc)
    real(rk), intent(in) :: g(3)
    real(rk) :: gc(3)
    gc = max(g, 0.0_rk)
    gc = gc/sum(gc)
  end function

  !> Whether slave edge (p, q) crossed master edge (a, b) during the step dt
  !> (positions x at its end, velocities v over it): the closest points of
  !> the two lines at the end, at alpha along p-q and beta along a-b, both
  !> inside their segments, and the gap g along n = (q-p) x (b-a) (turned to
  !> point from the master edge to where the slave edge was at the start)
  !> positive at the start (g0) and negative at the end (g1). Nearly
  !> parallel edges (the node-on-face contact's case) are left out.
  pure subroutine edge_crossing(xp, xq, xa, xb, vp, vq, va, vb, dt, alpha, beta, n, g0, g1, crossed)
    real(rk), intent(in) :: xp(3), xq(3), xa(3), xb(3), vp(3), vq(3), va(3), vb(3), dt
    real(rk), intent(out) :: alpha, beta, n(3), g0, g1
    logical, intent(out) :: crossed
    real(rk) :: d1(3), d2(3), r(3), aa, bb, cc, dd, ee, den, nn
    crossed = .false.
    alpha = 0; beta = 0; n = 0; g0 = 0; g1 = 0
    d1 = xq - xp
    d2 = xb - xa
    r = xp - xa
    aa = dot_product(d1, d1)
    bb = dot_product(d1, d2)
    cc = dot_product(d2, d2)
    dd = dot_product(d1, r)
    ee = dot_product(d2, r)
    den = aa*cc - bb*bb
    if (den <= 1.0e-6_rk*aa*cc) return          ! within 0.06 degrees of parallel
    alpha = (bb*ee - cc*dd)/den
    beta = (aa*ee - bb*dd)/den
    if (alpha < 0.0_rk .or. alpha > 1.0_rk .or. beta < 0.0_rk .or. beta > 1.0_rk) return
    n = cross(d1, d2)
    nn = norm2(n)
    n = n/nn
    g1 = dot_product(n, xp + alpha*d1 - xa - beta*d2)
    g0 = g1 - dt*dot_product(n, (1.0_rk - alpha)*vp + alpha*vq - (1.0_rk - beta)*va - beta*vb)
    if (g0 < 0.0_rk) then
      n = -n; g0 = -g0; g1 = -g1
    end if
    crossed = g1 < 0.0_rk
  end subroutine

  !> Shares w of an edge-to-edge impulse J n among the slave edge's nodes
  !> p, q (w(1:2), sum 1) and the master edge's a, b (w(3:4), sum -1): the
  !> points at alpha' along p-q and beta' along a-b whose join at the start
  !> of the step (positions x0) is parallel to n, so that the impulse exerts
  !> no moment about the start positions (as master_shares for a node);
  !> alpha, beta (the closest points at the end) where the edges turned so
  !> far that the start edges are within 60 degrees of a plane holding n.
  pure subroutine edge_shares(xp0, xq0, xa0, xb0, n, alpha, beta, w)
    real(rk), intent(in) :: xp0(3), xq0(3), xa0(3), xb0(3), n(3), alpha, beta
    real(rk), intent(out) :: w(4)
    real(rk) :: d1(3), d2(3), r(3), c(3), det, a0, b0
    ! p0 + a0 d1 - (a0 + b0 d2) = gamma n  <=>  a0 d1 - b0 d2 - gamma n = a0 - p0
    d1 = xq0 - xp0
    d2 = xb0 - xa0
    r = xa0 - xp0
    c = cross(d2, n)
    det = dot_product(d1, c)
    a0 = alpha
    b0 = beta
    if (abs(det) >= 0.5_rk*norm2(cross(d1, d2))) then
      a0 = dot_product(r, c)/det
      b0 = -dot_product(d1, cross(r, n))/det
    end if
    w = [1.0_rk - a0, a0, -(1.0_rk - b0), -b0]
  end subroutine

end module udar_contact_kernels
