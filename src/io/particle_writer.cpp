#include "src/io/particle_writer.hpp"

#include <petscsys.h>
#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "src/core/error.hpp"

namespace sph {

namespace {

PetscMPIInt comm_rank() {
  PetscMPIInt r;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}
PetscMPIInt comm_size() {
  PetscMPIInt s;
  MPI_Comm_size(PETSC_COMM_WORLD, &s);
  return s;
}

std::string frame_name(const std::string& base, int frame, const char* suffix) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "_%05d", frame);
  return base + buf + suffix;
}

vtkNew<vtkDoubleArray> scalar_array(const char* name, const std::vector<double>& values, std::size_t n) {
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfTuples(static_cast<vtkIdType>(n));
  for (std::size_t i = 0; i < n; ++i) a->SetValue(static_cast<vtkIdType>(i), values[i]);
  return a;
}

}  // namespace

template <int D>
ParticleWriter<D>::ParticleWriter(const std::string& output_dir, const std::string& basename)
    : dir_(output_dir), base_(basename) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec || !std::filesystem::is_directory(dir_))
    throw Error("cannot create output directory '" + dir_ + "' (" + ec.message() + "); choose another -output_dir");
}

template <int D>
std::string ParticleWriter<D>::write(const Particles<D>& P, double time, const std::vector<ScalarField>& extra) {
  const std::size_t n = P.n_owned;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(n));
  vtkNew<vtkCellArray> verts;
  vtkNew<vtkDoubleArray> velocity;
  velocity->SetName("velocity");
  velocity->SetNumberOfComponents(3);
  velocity->SetNumberOfTuples(static_cast<vtkIdType>(n));
  vtkNew<vtkIntArray> kind;
  kind->SetName("kind");
  kind->SetNumberOfTuples(static_cast<vtkIdType>(n));
  vtkNew<vtkIdTypeArray> id;
  id->SetName("id");
  id->SetNumberOfTuples(static_cast<vtkIdType>(n));
  for (std::size_t i = 0; i < n; ++i) {
    double x[3] = {0, 0, 0}, v[3] = {0, 0, 0};
    for (int a = 0; a < D; ++a) x[a] = P.x[i][a], v[a] = P.v[i][a];
    const vtkIdType k = static_cast<vtkIdType>(i);
    points->SetPoint(k, x);
    verts->InsertNextCell(1, &k);
    velocity->SetTuple(k, v);
    kind->SetValue(k, P.kind[i]);
    id->SetValue(k, static_cast<vtkIdType>(P.gid[i]));
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  poly->SetVerts(verts);
  vtkPointData* pd = poly->GetPointData();
  pd->AddArray(velocity);
  pd->AddArray(scalar_array("pressure", P.p, n));
  pd->AddArray(scalar_array("density", P.rho, n));
  pd->AddArray(scalar_array("mass", P.m, n));
  pd->AddArray(kind);
  pd->AddArray(id);
  for (const ScalarField& f : extra) pd->AddArray(scalar_array(f.name.c_str(), *f.values, n));
  vtkNew<vtkDoubleArray> t;
  t->SetName("TIME");
  t->SetNumberOfTuples(1);
  t->SetValue(0, time);
  poly->GetFieldData()->AddArray(t);

  const int frame = frames_written();
  const bool parallel = comm_size() > 1;
  const std::string piece = parallel ? frame_name(base_, frame, "") + "_r" + std::to_string(comm_rank()) + ".vtp"
                                     : frame_name(base_, frame, ".vtp");
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetFileName((dir_ + "/" + piece).c_str());
  writer->SetInputData(poly);
  writer->SetDataModeToAppended();
  writer->SetCompressorTypeToZLib();
  if (writer->Write() != 1) throw Error("cannot write " + dir_ + "/" + piece + "; check -output_dir");

  std::string listed = piece;
  if (parallel) {
    listed = frame_name(base_, frame, ".pvtp");
    if (comm_rank() == 0) {
      std::ofstream m(dir_ + "/" + listed);
      m << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PPolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <PPolyData GhostLevel=\"0\">\n    <PPointData>\n"
        << "      <PDataArray type=\"Float64\" Name=\"velocity\" NumberOfComponents=\"3\"/>\n"
        << "      <PDataArray type=\"Float64\" Name=\"pressure\"/>\n      <PDataArray type=\"Float64\" Name=\"density\"/>\n"
        << "      <PDataArray type=\"Float64\" Name=\"mass\"/>\n      <PDataArray type=\"Int32\" Name=\"kind\"/>\n"
        << "      <PDataArray type=\"Int64\" Name=\"id\"/>\n";
      for (const ScalarField& f : extra) m << "      <PDataArray type=\"Float64\" Name=\"" << f.name << "\"/>\n";
      m << "    </PPointData>\n    <PPoints>\n      <PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>\n"
        << "    </PPoints>\n";
      for (int r = 0; r < comm_size(); ++r)
        m << "    <Piece Source=\"" << frame_name(base_, frame, "") << "_r" << r << ".vtp\"/>\n";
      m << "  </PPolyData>\n</VTKFile>\n";
      if (!m) throw Error("cannot write " + dir_ + "/" + listed);
    }
  }
  frames_.emplace_back(time, listed);
  write_pvd();
  return dir_ + "/" + listed;
}

template <int D> void ParticleWriter<D>::write_pvd() const {
  if (comm_rank() != 0) return;
  const std::string path = dir_ + "/" + base_ + ".pvd", tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out.precision(17);
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
    for (const auto& f : frames_)
      out << "    <DataSet timestep=\"" << f.first << "\" part=\"0\" file=\"" << f.second << "\"/>\n";
    out << "  </Collection>\n</VTKFile>\n";
    if (!out) throw Error("cannot write " + path);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw Error("cannot rename " + tmp + " to " + path);
}

template class ParticleWriter<1>;
template class ParticleWriter<2>;
template class ParticleWriter<3>;

}  // namespace sph
