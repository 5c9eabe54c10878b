// BenchProximity: vtkDistanceFieldProximity frame after frame on two deforming bunnies
// that move into and out of contact (the deformation of Examples/Python/deforming_bunnies.py),
// per-frame time at each resolution, reusing the models' topology and with a fresh filter
// each frame, and on the same poses:
// - FCL's mesh-mesh distance() (BVHModel<OBBRSS>, built each frame, and refitted), when
//   the program was built with FCL (Debian's libfcl-dev): time and value when apart;
// - VTK's vtkCollisionDetectionFilter (contacts between triangles only): time and
//   whether it agrees on contact;
// - vtkPenetrationDepth (the minimum separating translation of convex solids) on two
//   boxes and on the bunnies' hulls, next to the maximum penetration.
// Prints figures; asserts nothing.
// Usage: BenchProximity MESH_DIR [FRAMES] [RESOLUTIONS, e.g. 128,256]
#include "../Cxx/UnitBoxMesh.h"
#include "vtkDistanceFieldProximity.h"
#include "vtkPenetrationDepth.h"

#include "vtkCleanPolyData.h"
#include "vtkCollisionDetectionFilter.h"
#include "vtkCubeSource.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkTransform.h"
#include "vtkTriangleFilter.h"
#include "vtkXMLPolyDataReader.h"

#ifdef DF_HAVE_FCL
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{
double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Frame f of 100: A waves in place; B, turned half a turn about the vertical (y) and
/// breathing, swings along x
/// from 1.2 (apart) to -0.3 (deep inside A) and back, twice.
void Pose(vtkPolyData* rest, int f, vtkPolyData* a, vtkPolyData* b)
{
  vtkNew<vtkPoints> pa, pb;
  pa->SetDataTypeToDouble();
  pb->SetDataTypeToDouble();
  const double phase = 2 * M_PI * f / 50.0;
  const double centre = 0.45 + 0.75 * std::cos(phase);
  const double breath = 1 + 0.1 * std::sin(0.3 * f);
  for (vtkIdType i = 0; i < rest->GetNumberOfPoints(); ++i)
  {
    double x[3];
    rest->GetPoint(i, x);
    pa->InsertNextPoint(x[0] + 0.04 * std::sin(6 * x[1] + 0.2 * f), x[1], x[2]);
    pb->InsertNextPoint(-x[0] * breath + centre, x[1] * breath + 0.05, -x[2] * breath);
  }
  a->ShallowCopy(rest);
  a->SetPoints(pa);
  b->ShallowCopy(rest);
  b->SetPoints(pb);
}

#ifdef DF_HAVE_FCL
using Model = fcl::BVHModel<fcl::OBBRSSd>;
std::shared_ptr<Model> ToFcl(vtkPolyData* mesh)
{
  auto model = std::make_shared<Model>();
  std::vector<fcl::Vector3d> points;
  std::vector<fcl::Triangle> triangles;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double x[3];
    mesh->GetPoint(i, x);
    points.emplace_back(x[0], x[1], x[2]);
  }
  vtkIdType n;
  const vtkIdType* ids;
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    mesh->GetCellPoints(c, n, ids);
    if (n == 3)
    {
      triangles.emplace_back(ids[0], ids[1], ids[2]);
    }
  }
  model->beginModel();
  model->addSubModel(points, triangles);
  model->endModel();
  return model;
}
#endif
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::printf("usage: %s MESH_DIR [FRAMES] [RESOLUTIONS] [BACKENDS: cpu,gpu]\n", argv[0]);
    return 2;
  }
  const int frames = argc > 2 ? std::atoi(argv[2]) : 100;
  std::vector<int> resolutions;
  std::stringstream list(argc > 3 ? argv[3] : "128,256");
  for (std::string item; std::getline(list, item, ',');)
  {
    resolutions.push_back(std::atoi(item.c_str()));
  }
  std::vector<std::string> backends;
  std::stringstream backendList(argc > 4 ? argv[4] : "cpu");
  for (std::string item; std::getline(backendList, item, ',');)
  {
    backends.push_back(item);
  }
  auto rest = vtkdf::testing::ReadUnitBoxMesh(std::string(argv[1]) + "/bunny_small.vtp");
  std::printf("two bunny_small (%lld triangles each), %d frames, %d threads (%s)\n",
    static_cast<long long>(rest->GetNumberOfCells()),
    frames,
    vtkSMPTools::GetEstimatedNumberOfThreads(),
    vtkSMPTools::GetBackend());

  std::vector<double> separation(frames, 0);
  std::vector<int> colliding(frames, 0);
  for (const std::string& backend : backends)
    for (const int resolution : resolutions)
    {
      for (const bool contacts : { true, false })
      {
        const int backendValue = backend == "gpu" ? vtkDistanceFieldProximity::BACKEND_GPU
                                                  : vtkDistanceFieldProximity::BACKEND_CPU;
        vtkNew<vtkDistanceFieldProximity> kept;
        kept->SetBackend(backendValue);
        kept->SetResolution(resolution);
        kept->SetContactPoints(contacts);
        double total = 0, worst = 0, fresh = 0, queries = 0, inside = 0, sent = 0, freshSent = 0;
        int touching = 0;
        for (int f = 0; f < frames; ++f)
        {
          vtkNew<vtkPolyData> a, b;
          Pose(rest, f, a, b);
          kept->SetModelAData(a);
          kept->SetModelBData(b);
          const double start = Now();
          kept->Update();
          const double seconds = Now() - start;
          total += seconds;
          worst = std::max(worst, seconds);
          if (kept->GetErrorCode() != 0)
          {
            std::printf("the filter failed on the %s\n", backend.c_str());
            return 1;
          }
          queries += static_cast<double>(kept->GetLastPointQueries());
          sent += f > 0 ? static_cast<double>(kept->GetLastBytesToDevice()) : 0;
          inside += kept->GetOutput(1)->GetNumberOfPoints();
          touching += kept->GetLastColliding() ? 1 : 0;
          separation[f] = kept->GetLastSeparationDistance();
          colliding[f] = kept->GetLastColliding() ? 1 : 0;
          if (contacts)
          {
            vtkNew<vtkDistanceFieldProximity> once;
            once->SetBackend(backendValue);
            once->SetResolution(resolution);
            once->SetModelAData(a);
            once->SetModelBData(b);
            const double t0 = Now();
            once->Update();
            fresh += Now() - t0;
            freshSent += f > 0 ? static_cast<double>(once->GetLastBytesToDevice()) : 0;
          }
        }
        std::printf("%s resolution %4d contacts %-3s  per frame: mean %.1f ms, max %.1f ms%s  "
                    "exact point queries %.0f, contact samples %.0f  colliding in %d frames\n",
          backend.c_str(),
          resolution,
          contacts ? "on" : "off",
          1e3 * total / frames,
          1e3 * worst,
          contacts
            ? (" (a fresh filter each frame: " + std::to_string(1e3 * fresh / frames) + " ms)")
                .c_str()
            : "",
          queries / frames,
          inside / frames,
          touching);
        if (backend == "gpu" && contacts && frames > 1)
        {
          std::printf(
            "    sent to the GPU a frame after the first: %.0f kB (a fresh filter: %.0f kB)\n",
            1e-3 * sent / (frames - 1),
            1e-3 * freshSent / (frames - 1));
        }
      }
    }

  // VTK's collision filter on the same poses: contacts between triangles.
  {
    double total = 0;
    int agree = 0, contactsFrames = 0;
    for (int f = 0; f < frames; ++f)
    {
      vtkNew<vtkPolyData> a, b;
      Pose(rest, f, a, b);
      vtkNew<vtkCollisionDetectionFilter> collide;
      collide->SetInputData(0, a);
      collide->SetInputData(1, b);
      vtkNew<vtkMatrix4x4> identity0, identity1;
      collide->SetMatrix(0, identity0);
      collide->SetMatrix(1, identity1);
      collide->SetCollisionModeToFirstContact();
      const double start = Now();
      collide->Update();
      total += Now() - start;
      const bool contact = collide->GetNumberOfContacts() > 0;
      contactsFrames += contact ? 1 : 0;
      agree += contact == (colliding[f] != 0) ? 1 : 0;
    }
    std::printf("vtkCollisionDetectionFilter (first contact): mean %.1f ms a frame, contact "
                "in %d frames, agrees with Colliding in %d of %d (it has no containment)\n",
      1e3 * total / frames,
      contactsFrames,
      agree,
      frames);
  }
  // vtkPenetrationDepth on the same pairs: the minimum separating translation of convex
  // solids (the bunnies through their hulls), next to the maximum penetration here.
  {
    auto box = [](double x0)
    {
      vtkNew<vtkCubeSource> cube;
      cube->SetBounds(x0, x0 + 1, 0.2, 0.8, 0.2, 0.8);
      vtkNew<vtkCleanPolyData> clean;
      clean->SetInputConnection(cube->GetOutputPort());
      vtkNew<vtkTriangleFilter> triangles;
      triangles->SetInputConnection(clean->GetOutputPort());
      triangles->Update();
      auto mesh = vtkSmartPointer<vtkPolyData>::New();
      mesh->DeepCopy(triangles->GetOutput());
      return mesh;
    };
    vtkNew<vtkPolyData> a, b;
    Pose(rest, 25, a, b);
    const std::pair<vtkSmartPointer<vtkPolyData>, vtkSmartPointer<vtkPolyData>> pairs[2] = {
      { box(0), box(0.7) }, { a.Get(), b.Get() }
    };
    const char* names[2] = { "boxes overlapping by 0.3", "bunnies, frame 25 (PD of hulls)" };
    for (int k = 0; k < 2; ++k)
    {
      vtkNew<vtkDistanceFieldProximity> proximity;
      proximity->SetResolution(128);
      proximity->SetModelAData(pairs[k].first);
      proximity->SetModelBData(pairs[k].second);
      double t0 = Now();
      proximity->Update();
      const double proximitySeconds = Now() - t0;
      vtkNew<vtkPenetrationDepth> depth;
      depth->SetSolidPData(pairs[k].first);
      depth->SetSolidQData(pairs[k].second);
      depth->SetBackendToCPU();
      depth->SetUseConvexHulls(k == 1);
      t0 = Now();
      depth->Update();
      const double depthSeconds = Now() - t0;
      std::printf("%s: proximity (128) max penetration AB %.6f BA %.6f in %.1f ms; "
                  "vtkPenetrationDepth %.6f in %.1f ms\n",
        names[k],
        proximity->GetLastPenetrationAB(),
        proximity->GetLastPenetrationBA(),
        1e3 * proximitySeconds,
        depth->GetLastPenetrationDepth(),
        1e3 * depthSeconds);
    }
  }
#ifdef DF_HAVE_FCL
  {
    double build = 0, query = 0, worst = 0;
    int apart = 0;
    for (int f = 0; f < frames; ++f)
    {
      vtkNew<vtkPolyData> a, b;
      Pose(rest, f, a, b);
      const double t0 = Now();
      auto ma = ToFcl(a), mb = ToFcl(b);
      const double t1 = Now();
      fcl::CollisionObjectd oa(ma, fcl::Transform3d::Identity());
      fcl::CollisionObjectd ob(mb, fcl::Transform3d::Identity());
      fcl::DistanceRequestd request(true);
      fcl::DistanceResultd result;
      fcl::distance(&oa, &ob, request, result);
      const double t2 = Now();
      build += t1 - t0;
      query += t2 - t1;
      if (!colliding[f])
      {
        ++apart;
        worst = std::max(
          worst, std::fabs(result.min_distance - separation[f]) / std::max(1e-300, separation[f]));
      }
    }
    std::printf("FCL distance (BVHModel<OBBRSS> built each frame): build %.1f ms + query %.1f ms "
                "a frame; on the %d frames apart its distance differs from "
                "SeparationDistance by at most %.3g relative\n",
      1e3 * build / frames,
      1e3 * query / frames,
      apart,
      worst);
  }
#else
  std::printf("FCL: not built in (install libfcl-dev and reconfigure)\n");
#endif
  return 0;
}
