!> The boundary faces contact surfaces are made of (udar_contact_setup
!> exterior_faces), for tetrahedra and for the 2D triangles (issue 14's
!> contact): on the structured elastic bars, every face counted once, their
!> areas (lengths) adding up to the bar's surface (outline), and each one's
!> normal pointing out of the body (counter-clockwise seen from outside;
!> in 2D the normal of edge a -> b is (dy, -dx)).
program test_exterior_faces
  use udar_kinds, only: rk
  use udar_strings, only: itoa, r2s
  use udar_config, only: config_t
  use udar_domain, only: domain_t
  use udar_vectors, only: cross
  use udar_contact_setup, only: exterior_faces
  use unit_domains, only: elastic_bar_mesh_domain, elastic_bar_2d_mesh_domain
  use unit_checks, only: check, check_summary
  implicit none
  type(config_t) :: cfg
  type(domain_t) :: glob
  character(len=512) :: unit_dir
  integer, allocatable :: face(:,:), face_part(:)
  integer :: nf, k, outward
  real(rk) :: total, c(3), centre(3), n(3), e(3)

  call get_command_argument(1, unit_dir)
  ! 3D: the square bar 10 x 10 x 100 mm, 2 x 2 x 200 cells of tetrahedra
  call elastic_bar_mesh_domain(trim(unit_dir), cfg, glob)
  call exterior_faces(glob, face, face_part, nf)
  centre = [0.005_rk, 0.005_rk, 0.05_rk]
  total = 0
  outward = 0
  do k = 1, nf
    n = cross(glob%nd_x0(:,face(2,k)) - glob%nd_x0(:,face(1,k)), glob%nd_x0(:,face(3,k)) - glob%nd_x0(:,face(1,k)))
    total = total + 0.5_rk*norm2(n)
    c = (glob%nd_x0(:,face(1,k)) + glob%nd_x0(:,face(2,k)) + glob%nd_x0(:,face(3,k)))/3.0_rk
    if (dot_product(n, c - centre) > 0.0_rk) outward = outward + 1
  end do
  call check('tet_boundary_faces', size(face, 1) == 3 .and. nf == 3216 .and. abs(total/4.2e-3_rk - 1) < 1e-12_rk &
             .and. outward == nf, itoa(nf)//' faces (3216), area '//r2s(total)//' m2 (4.2e-3), '//itoa(outward)// &
             ' pointing out')
  ! 2D: the round bar's meridian section, 5 x 200 cells of triangles
  call elastic_bar_2d_mesh_domain(trim(unit_dir), cfg, glob)
  call exterior_faces(glob, face, face_part, nf)
  centre = [0.0025_rk, 0.05_rk, 0.0_rk]
  total = 0
  outward = 0
  do k = 1, nf
    e = glob%nd_x0(:,face(2,k)) - glob%nd_x0(:,face(1,k))
    total = total + norm2(e)
    c = 0.5_rk*(glob%nd_x0(:,face(1,k)) + glob%nd_x0(:,face(2,k)))
    if (dot_product([e(2), -e(1)], c(1:2) - centre(1:2)) > 0.0_rk) outward = outward + 1
  end do
  call check('triangle_boundary_edges', size(face, 1) == 2 .and. nf == 410 .and. abs(total/0.21_rk - 1) < 1e-12_rk &
             .and. outward == nf, itoa(nf)//' edges (410), outline '//r2s(total)//' m (0.21), '//itoa(outward)// &
             ' with their normal (dy, -dx) pointing out')
  call check_summary()
end program test_exterior_faces
