#include "src/io/particle_writer.hpp"

#include <petscsys.h>
#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkTypeInt64Array.h>
#include <vtkXMLPolyDataWriter.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <system_error>

#include "src/core/error.hpp"
#include "src/io/vtk_files.hpp"

namespace sph {

namespace {

std::string piece_name(const std::string& base, int frame, int rank) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "_r%04d.vtp", rank);
  return frame_stem(base, frame) + buf;
}

// The VTK XML type name that vtkXMLWriter uses for an array (for the hand-written .pvtp).
const char* xml_type(vtkDataArray* a) {
  switch (a->GetDataType()) {
    case VTK_DOUBLE: return "Float64";
    case VTK_FLOAT: return "Float32";
    case VTK_INT: return "Int32";
    case VTK_LONG:
    case VTK_LONG_LONG:
    case VTK_ID_TYPE: return a->GetDataTypeSize() == 8 ? "Int64" : "Int32";
    default: throw Error(std::string("internal: no VTK XML type for output array ") + a->GetName());
  }
}

vtkNew<vtkDoubleArray> scalar_array(const std::string& name, const std::vector<double>& values, std::size_t n) {
  vtkNew<vtkDoubleArray> a;
  a->SetName(name.c_str());
  a->SetNumberOfTuples(static_cast<vtkIdType>(n));
  for (std::size_t i = 0; i < n; ++i) a->SetValue(static_cast<vtkIdType>(i), values[i]);
  return a;
}

}  // namespace

template <int D> ParticleWriter<D>::ParticleWriter(const std::string& output_dir, const std::string& basename)
    : dir_(output_dir.empty() ? std::string(".") : output_dir), base_(basename), series_(dir_, base_) {
  PetscMPIInt r = 0, s = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  MPI_Comm_size(PETSC_COMM_WORLD, &s);
  rank_ = r, size_ = s;
  if (base_.empty() || base_.find('/') != std::string::npos)
    throw Error("internal: particle output basename '" + base_ + "' must be a plain, non-empty file name");
  // Every rank may try: create_directories tolerates a directory that already exists, and if two ranks
  // race, the loser's error is ignored as long as the directory is there afterwards.
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  std::error_code ec2;
  if (!std::filesystem::is_directory(dir_, ec2))
    throw Error("cannot create output directory '" + dir_ + "'" + (ec ? " (" + ec.message() + ")" : std::string()) +
                "; choose another -output_dir");
}

namespace {

// The owned particles as VTK polydata: one vertex cell each (ParaView renders them as points), their
// velocity, pressure, density, mass, kind and id, the extra fields, and the time as field data.
template <int D>
vtkSmartPointer<vtkPolyData> particle_poly(const Particles<D>& P, double time, const std::vector<ScalarField>& extra) {
  const std::size_t n = P.n_owned;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(n));
  vtkNew<vtkCellArray> verts;
  verts->AllocateExact(static_cast<vtkIdType>(n), static_cast<vtkIdType>(n));
  vtkNew<vtkDoubleArray> velocity;
  velocity->SetName("velocity");
  velocity->SetNumberOfComponents(3);
  velocity->SetNumberOfTuples(static_cast<vtkIdType>(n));
  vtkNew<vtkIntArray> kind;
  kind->SetName("kind");
  kind->SetNumberOfTuples(static_cast<vtkIdType>(n));
  vtkNew<vtkTypeInt64Array> id;
  id->SetName("id");
  id->SetNumberOfTuples(static_cast<vtkIdType>(n));
  for (std::size_t i = 0; i < n; ++i) {
    double x[3] = {0, 0, 0}, v[3] = {0, 0, 0};
    for (int a = 0; a < D; ++a) x[a] = P.x[i][a], v[a] = P.v[i][a];
    const vtkIdType k = static_cast<vtkIdType>(i);
    points->SetPoint(k, x);
    verts->InsertNextCell(1, &k);
    velocity->SetTypedTuple(k, v);
    kind->SetValue(k, P.kind[i]);
    id->SetValue(k, static_cast<vtkTypeInt64>(P.id[i]));
  }
  vtkSmartPointer<vtkPolyData> poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetVerts(verts);
  vtkPointData* pd = poly->GetPointData();
  pd->AddArray(velocity);
  pd->AddArray(scalar_array("pressure", P.p, n));
  pd->AddArray(scalar_array("density", P.rho, n));
  pd->AddArray(scalar_array("mass", P.m, n));
  pd->AddArray(kind);
  pd->AddArray(id);
  for (const ScalarField& f : extra) pd->AddArray(scalar_array(f.name, *f.values, n));
  vtkNew<vtkDoubleArray> t;
  t->SetName("TIME");
  t->SetNumberOfTuples(1);
  t->SetValue(0, time);
  poly->GetFieldData()->AddArray(t);
  return poly;
}

// The .pvtp index of a frame written in `ranks` pieces: the point arrays' names and types, and the pieces.
std::string parallel_index(vtkPointData* pd, const std::string& base, int frame, int ranks) {
  std::string m =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"PPolyData\" version=\"0.1\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
      "  <PPolyData GhostLevel=\"0\">\n"
      "    <PPointData>\n";
  for (int k = 0; k < pd->GetNumberOfArrays(); ++k) {
    vtkDataArray* a = pd->GetArray(k);
    m += "      <PDataArray type=\"" + std::string(xml_type(a)) + "\" Name=\"" + xml_attr(a->GetName()) + "\"";
    if (a->GetNumberOfComponents() > 1)
      m += " NumberOfComponents=\"" + std::to_string(a->GetNumberOfComponents()) + "\"";
    m += "/>\n";
  }
  m += "    </PPointData>\n"
       "    <PPoints>\n"
       "      <PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>\n"
       "    </PPoints>\n";
  for (int r = 0; r < ranks; ++r) m += "    <Piece Source=\"" + xml_attr(piece_name(base, frame, r)) + "\"/>\n";
  m += "  </PPolyData>\n</VTKFile>\n";
  return m;
}

}  // namespace

template <int D>
std::string ParticleWriter<D>::write(const Particles<D>& P, double time, const std::vector<ScalarField>& extra) {
  const std::size_t n = P.n_owned;
  for (const ScalarField& f : extra)
    if (!f.values || f.values->size() < n)
      throw Error("internal: output field '" + f.name + "' has " + std::to_string(f.values ? f.values->size() : 0) +
                  " values for " + std::to_string(n) + " particles");
  const vtkSmartPointer<vtkPolyData> poly = particle_poly(P, time, extra);
  const int frame = frames_written();
  const bool parallel = size_ > 1;
  const std::string own = parallel ? piece_name(base_, frame, rank_) : frame_stem(base_, frame) + ".vtp";
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(poly);
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();  // raw binary
  writer->SetCompressorTypeToZLib();
  writer->SetHeaderTypeToUInt64();  // no 4 GiB limit on a block
  write_frame(writer, dir_ + "/" + own);
  std::string listed = own;
  if (parallel) {
    listed = frame_stem(base_, frame) + ".pvtp";
    if (rank_ == 0) write_atomically(dir_ + "/" + listed, parallel_index(poly->GetPointData(), base_, frame, size_));
  }
  series_.add(time, listed);
  return dir_ + "/" + listed;
}

template <int D> void ParticleWriter<D>::resume(double t) { series_.resume(t); }

template class ParticleWriter<1>;
template class ParticleWriter<2>;
template class ParticleWriter<3>;

}  // namespace sph
