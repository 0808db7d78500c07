#include "src/io/surface_writer.hpp"

#include <petscsys.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

namespace sph {

SurfaceWriter::SurfaceWriter(const std::string& output_dir, const std::string& body)
    : dir_(output_dir.empty() ? std::string(".") : output_dir), base_("body_" + body), series_(dir_, base_) {}

void SurfaceWriter::write(const SurfaceMesh& surface, double time, const std::vector<double>* pressure,
                          const std::vector<std::array<double, 3>>* shear) {
  const std::string file = frame_stem(base_, series_.size()) + ".vtp";
  PetscMPIInt rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0) {
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    for (const auto& x : surface.points) points->InsertNextPoint(x.data());
    vtkNew<vtkCellArray> cells;
    for (const auto& c : surface.cells) {
      std::vector<vtkIdType> ids(c.begin(), c.end());
      cells->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    }
    vtkNew<vtkPolyData> poly;
    poly->SetPoints(points);
    if (surface.lines) poly->SetLines(cells);
    else poly->SetPolys(cells);
    if (pressure && pressure->size() == surface.cells.size()) {
      const bool sheared = shear && shear->size() == surface.cells.size();
      vtkNew<vtkDoubleArray> p, viscous, traction;
      p->SetName("pressure");
      viscous->SetName("shear");
      viscous->SetNumberOfComponents(3);
      traction->SetName("traction");
      traction->SetNumberOfComponents(3);
      for (std::size_t c = 0; c < surface.cells.size(); ++c) {
        const Eigen::Vector3d an = face_area_normal(surface, surface.cells[c]);
        const double area = an.norm();
        Eigen::Vector3d t = area > 0.0 ? Eigen::Vector3d(-(*pressure)[c] / area * an) : Eigen::Vector3d::Zero();
        p->InsertNextValue((*pressure)[c]);
        if (sheared) {
          const Eigen::Vector3d tau((*shear)[c].data());
          viscous->InsertNextTuple(tau.data());
          t += tau;
        }
        traction->InsertNextTuple(t.data());
      }
      poly->GetCellData()->AddArray(p);
      if (sheared) poly->GetCellData()->AddArray(viscous);
      poly->GetCellData()->AddArray(traction);
    }
    vtkNew<vtkDoubleArray> t;
    t->SetName("TIME");
    t->SetNumberOfTuples(1);
    t->SetValue(0, time);
    poly->GetFieldData()->AddArray(t);
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetInputData(poly);
    writer->SetDataModeToAppended();
    writer->EncodeAppendedDataOff();
    write_frame(writer, dir_ + "/" + file);
  }
  series_.add(time, file);
}

}  // namespace sph
