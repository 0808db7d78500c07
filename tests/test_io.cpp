// Output files: particle frames (.vtp/.pvtp + .pvd), the CSV time series and JSON summaries are read
// back with independent readers (VTK's XML readers, strtod, nlohmann::json::parse) and compared with
// what was written. Runs on any number of ranks (mpirun -n 2 build/tests/test_io checks the pieces
// and the hand-written .pvtp master).
#include <gtest/gtest.h>
#include <petscsys.h>
#include <unistd.h>
#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPPolyDataReader.h>
#include <vtkXMLPolyDataReader.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "src/core/error.hpp"
#include "src/io/csv_writer.hpp"
#include "src/io/json_file.hpp"
#include "src/io/particle_writer.hpp"

namespace fs = std::filesystem;
using sph::Particles;
using sph::ScalarField;
using sph::Vector;

namespace {

int rank() {
  PetscMPIInt r = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}
int ranks() {
  PetscMPIInt s = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &s);
  return s;
}

// A fresh directory under the build tree, shared by all ranks, unique to this process and test.
std::string fresh_dir(const std::string& name) {
  long pid = rank() == 0 ? static_cast<long>(getpid()) : 0;
  MPI_Bcast(&pid, 1, MPI_LONG, 0, PETSC_COMM_WORLD);
  const fs::path dir = fs::path(SPH_BINARY_DIR) / "test_io_output" / (name + "-" + std::to_string(pid));
  if (rank() == 0) {
    fs::remove_all(dir);
    fs::create_directories(dir.parent_path());
  }
  MPI_Barrier(PETSC_COMM_WORLD);
  return dir.string();
}

void remove_dir(const std::string& dir) {
  MPI_Barrier(PETSC_COMM_WORLD);
  if (rank() == 0 && !::testing::Test::HasFailure()) fs::remove_all(dir);
}

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// n owned particles with distinct values on every field, plus a few ghosts that must not be written.
// Rank r owns global indices [r n, (r+1) n).
template <int D> Particles<D> make_particles(int n) {
  Particles<D> P;
  const int r = rank();
  for (int i = 0; i < n; ++i) {
    Vector<D> x, v;
    for (int a = 0; a < D; ++a) {
      x[a] = 0.1 * i + 0.37 * a + 0.001 * (a + 1) * i * i + 10.0 * r;
      v[a] = -0.5 + 0.03 * i - 0.7 * a + 0.25 * r;
    }
    const int k = (i % 3 == 0) ? sph::kWall : sph::kFluid;
    P.add(x, v, 1.0 + 0.01 * i + r, 1000.0 + 0.5 * i - r, -3.25 + 0.125 * i + 7 * r, k);
  }
  P.n_global = static_cast<sph::GlobalIndex>(n) * ranks();
  P.first_gid = static_cast<sph::GlobalIndex>(n) * r;
  for (int i = 0; i < n; ++i) P.gid[i] = P.first_gid + i, P.id[i] = 1000 + P.gid[i];  // labels differ from gids
  P.set_ghost_count(3);
  for (std::size_t g = P.n_owned; g < P.size(); ++g) {
    P.x[g] = Vector<D>::Constant(-99.0);
    P.v[g] = Vector<D>::Constant(-99.0);
    P.m[g] = P.rho[g] = P.p[g] = -99.0;
    P.kind[g] = 7;
    P.gid[g] = P.id[g] = 424242;
  }
  return P;
}

// Checks a read-back frame against the owned particles and the extra field (exact: the files are binary).
template <int D> void expect_frame_matches(vtkPolyData* poly, const Particles<D>& P, const std::string& extra_name,
                                           const std::vector<double>& extra, double time) {
  ASSERT_NE(poly, nullptr);
  const vtkIdType n = static_cast<vtkIdType>(P.n_owned);
  ASSERT_EQ(poly->GetNumberOfPoints(), n);
  EXPECT_EQ(poly->GetNumberOfVerts(), n);  // one vertex cell per particle
  EXPECT_EQ(poly->GetVerts()->GetNumberOfConnectivityIds(), n);

  vtkPointData* pd = poly->GetPointData();
  vtkDataArray* vel = pd->GetArray("velocity");
  vtkDataArray* pres = pd->GetArray("pressure");
  vtkDataArray* dens = pd->GetArray("density");
  vtkDataArray* mass = pd->GetArray("mass");
  vtkDataArray* kind = pd->GetArray("kind");
  vtkDataArray* id = pd->GetArray("id");
  vtkDataArray* ex = pd->GetArray(extra_name.c_str());
  for (vtkDataArray* a : {vel, pres, dens, mass, kind, id, ex}) ASSERT_NE(a, nullptr);
  EXPECT_EQ(vel->GetNumberOfComponents(), 3);
  for (vtkDataArray* a : {vel, pres, dens, mass, ex}) EXPECT_EQ(a->GetDataType(), VTK_DOUBLE) << a->GetName();
  for (vtkDataArray* a : {pres, dens, mass, kind, id, ex}) EXPECT_EQ(a->GetNumberOfComponents(), 1) << a->GetName();
  EXPECT_NE(vtkIntArray::SafeDownCast(kind), nullptr) << "kind must be an int array";
  EXPECT_EQ(id->GetDataTypeSize(), 8) << "id must be a 64-bit integer array";
  EXPECT_TRUE(id->GetDataType() == VTK_LONG_LONG || id->GetDataType() == VTK_LONG || id->GetDataType() == VTK_ID_TYPE);
  for (vtkDataArray* a : {vel, pres, dens, mass, kind, id, ex}) ASSERT_EQ(a->GetNumberOfTuples(), n) << a->GetName();

  for (vtkIdType i = 0; i < n; ++i) {
    double x[3];
    poly->GetPoint(i, x);
    for (int a = 0; a < 3; ++a) {
      const double want_x = a < D ? P.x[i][a] : 0.0, want_v = a < D ? P.v[i][a] : 0.0;
      EXPECT_EQ(x[a], want_x) << "point " << i << " component " << a;
      EXPECT_EQ(vel->GetComponent(i, a), want_v) << "velocity " << i << " component " << a;
    }
    EXPECT_EQ(pres->GetComponent(i, 0), P.p[i]);
    EXPECT_EQ(dens->GetComponent(i, 0), P.rho[i]);
    EXPECT_EQ(mass->GetComponent(i, 0), P.m[i]);
    EXPECT_EQ(vtkIntArray::SafeDownCast(kind)->GetValue(i), P.kind[i]);
    EXPECT_EQ(static_cast<long long>(id->GetComponent(i, 0)), static_cast<long long>(P.id[i]));
    EXPECT_EQ(ex->GetComponent(i, 0), extra[i]);
  }
  vtkDataArray* t = poly->GetFieldData()->GetArray("TIME");
  ASSERT_NE(t, nullptr);
  ASSERT_EQ(t->GetNumberOfTuples(), 1);
  EXPECT_EQ(t->GetComponent(0, 0), time);
}

vtkSmartPointer<vtkPolyData> read_vtp(const std::string& path) {
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  return reader->GetOutput();
}

vtkSmartPointer<vtkPolyData> read_pvtp(const std::string& path) {
  vtkNew<vtkXMLPPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  return reader->GetOutput();
}

struct PvdEntry {
  double timestep;
  std::string file;
};

std::vector<PvdEntry> parse_pvd(const std::string& text) {
  std::vector<PvdEntry> out;
  const std::regex dataset(R"re(<DataSet\s[^>]*timestep="([^"]*)"[^>]*file="([^"]*)"[^>]*/>)re");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), dataset); it != std::sregex_iterator(); ++it)
    out.push_back({std::stod((*it)[1].str()), (*it)[2].str()});
  return out;
}

std::size_t count_occurrences(const std::string& text, const std::string& what) {
  std::size_t count = 0;
  for (std::size_t pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1)) ++count;
  return count;
}

template <int D> void round_trip_frame(const std::string& test_name, int n) {
  const std::string dir = fresh_dir(test_name) + "/nested/out";  // parents are created too
  const Particles<D> P = make_particles<D>(n);
  std::vector<double> vort(P.size());
  for (std::size_t i = 0; i < vort.size(); ++i) vort[i] = std::sin(1.0 + i) * 1e-3;

  sph::ParticleWriter<D> writer(dir);
  ASSERT_TRUE(fs::is_directory(dir));
  const double time = 0.1234567890123;
  const std::string path = writer.write(P, time, {ScalarField{"vorticity", &vort}});
  EXPECT_EQ(writer.frames_written(), 1);
  MPI_Barrier(PETSC_COMM_WORLD);  // every piece is on disk before anyone reads the master

  if (ranks() == 1) {
    EXPECT_EQ(path, dir + "/particles_00000.vtp");
    ASSERT_TRUE(fs::is_regular_file(path));
    expect_frame_matches<D>(read_vtp(path), P, "vorticity", vort, time);
  } else {
    char piece[64];
    std::snprintf(piece, sizeof piece, "/particles_00000_r%04d.vtp", rank());
    EXPECT_EQ(path, dir + "/particles_00000.pvtp");
    ASSERT_TRUE(fs::is_regular_file(dir + piece));
    expect_frame_matches<D>(read_vtp(dir + piece), P, "vorticity", vort, time);
    if (rank() == 0) {
      // The master joins every rank's piece: every particle label once, same arrays.
      vtkSmartPointer<vtkPolyData> all = read_pvtp(path);
      ASSERT_EQ(all->GetNumberOfPoints(), static_cast<vtkIdType>(P.n_global));
      vtkDataArray* id = all->GetPointData()->GetArray("id");
      ASSERT_NE(id, nullptr);
      std::set<long long> ids;
      for (vtkIdType i = 0; i < all->GetNumberOfPoints(); ++i)
        ids.insert(static_cast<long long>(id->GetComponent(i, 0)));
      EXPECT_EQ(ids.size(), static_cast<std::size_t>(P.n_global));
      EXPECT_EQ(*ids.begin(), 1000);
      EXPECT_EQ(*ids.rbegin(), 1000 + static_cast<long long>(P.n_global) - 1);
      for (const char* name : {"velocity", "pressure", "density", "mass", "kind", "vorticity"})
        EXPECT_NE(all->GetPointData()->GetArray(name), nullptr) << name;
    }
  }
  if (rank() == 0) {
    const std::vector<PvdEntry> frames = parse_pvd(slurp(dir + "/particles.pvd"));
    ASSERT_EQ(frames.size(), 1u);
    EXPECT_EQ(frames[0].timestep, time);
    EXPECT_EQ(dir + "/" + frames[0].file, path);
  }
  remove_dir(fs::path(dir).parent_path().parent_path().string());
}

}  // namespace

TEST(IoParticleWriter, RoundTrip1D) { round_trip_frame<1>("rt1d", 17); }
TEST(IoParticleWriter, RoundTrip2D) { round_trip_frame<2>("rt2d", 30); }
TEST(IoParticleWriter, RoundTrip3D) { round_trip_frame<3>("rt3d", 41); }

TEST(IoParticleWriter, PvdListsEveryFrameWithItsTime) {
  const std::string dir = fresh_dir("pvd");
  Particles<2> P = make_particles<2>(12);
  sph::ParticleWriter<2> writer(dir, "fluid");
  const std::vector<double> times = {0.0, 0.125, 1.0 / 3.0};
  std::vector<std::string> paths;
  for (std::size_t f = 0; f < times.size(); ++f) {
    for (std::size_t i = 0; i < P.n_owned; ++i) P.p[i] = 10.0 * f + i;  // the frames differ
    paths.push_back(writer.write(P, times[f]));
    MPI_Barrier(PETSC_COMM_WORLD);
    if (rank() == 0) {  // the .pvd is valid (and complete so far) after every frame
      const std::string text = slurp(dir + "/fluid.pvd");
      EXPECT_EQ(count_occurrences(text, "<DataSet"), f + 1);
      EXPECT_NE(text.find("</VTKFile>"), std::string::npos);
    }
  }
  EXPECT_EQ(writer.frames_written(), 3);
  const std::string ext = ranks() == 1 ? ".vtp" : ".pvtp";
  for (int f = 0; f < 3; ++f) {
    char want[64];
    std::snprintf(want, sizeof want, "/fluid_%05d", f);
    EXPECT_EQ(paths[f], dir + want + ext);
  }
  if (rank() == 0) {
    const std::string text = slurp(dir + "/fluid.pvd");
    EXPECT_NE(text.find("type=\"Collection\""), std::string::npos);
    EXPECT_EQ(count_occurrences(text, "<DataSet"), 3u);
    const std::vector<PvdEntry> frames = parse_pvd(text);
    ASSERT_EQ(frames.size(), 3u);
    for (int f = 0; f < 3; ++f) {
      EXPECT_EQ(frames[f].timestep, times[f]);  // written with 17 digits: exact
      EXPECT_EQ(dir + "/" + frames[f].file, paths[f]);
      EXPECT_TRUE(fs::is_regular_file(paths[f])) << paths[f];
      EXPECT_EQ(frames[f].file.find('/'), std::string::npos) << "file names are relative to the .pvd";
    }
    EXPECT_FALSE(fs::exists(dir + "/fluid.pvd.tmp"));
    if (ranks() == 1) {  // the last frame holds the last pressures and time
      vtkSmartPointer<vtkPolyData> last = read_vtp(paths[2]);
      EXPECT_EQ(last->GetPointData()->GetArray("pressure")->GetComponent(5, 0), 25.0);
      EXPECT_EQ(last->GetFieldData()->GetArray("TIME")->GetComponent(0, 0), 1.0 / 3.0);
    }
  }
  remove_dir(dir);
}

TEST(IoParticleWriter, EmptyRankWritesAValidFrame) {
  const std::string dir = fresh_dir("empty");
  Particles<3> P;
  sph::ParticleWriter<3> writer(dir);
  const std::string path = writer.write(P, 2.5);
  MPI_Barrier(PETSC_COMM_WORLD);
  if (ranks() == 1) {
    vtkSmartPointer<vtkPolyData> poly = read_vtp(path);
    EXPECT_EQ(poly->GetNumberOfPoints(), 0);
    EXPECT_EQ(poly->GetFieldData()->GetArray("TIME")->GetComponent(0, 0), 2.5);
  }
  remove_dir(dir);
}

TEST(IoParticleWriter, ExtraFieldTooShortThrows) {
  const std::string dir = fresh_dir("short");
  const Particles<2> P = make_particles<2>(10);
  const std::vector<double> few(4, 1.0);
  sph::ParticleWriter<2> writer(dir);
  EXPECT_THROW(writer.write(P, 0.0, {ScalarField{"few", &few}}), sph::Error);
  EXPECT_THROW(writer.write(P, 0.0, {ScalarField{"null", nullptr}}), sph::Error);
  EXPECT_EQ(writer.frames_written(), 0);
  remove_dir(dir);
}

TEST(IoParticleWriter, BadOutputDirectoryThrowsNamingIt) {
  const std::string dir = fresh_dir("baddir");
  if (rank() == 0) fs::create_directories(dir);
  MPI_Barrier(PETSC_COMM_WORLD);
  const std::string file = dir + "/a_regular_file";
  if (rank() == 0) std::ofstream(file) << "not a directory\n";
  MPI_Barrier(PETSC_COMM_WORLD);
  const std::string bad = file + "/out";
  try {
    sph::ParticleWriter<2> writer(bad);
    ADD_FAILURE() << "no error for an output directory under a regular file";
  } catch (const sph::Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(bad), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "one-line message: " << msg;
  }
  if (rank() == 0) {  // the other writers report a bad path too
    EXPECT_THROW(sph::CsvWriter(bad + "/timeseries.csv", {"t"}), sph::Error);
    EXPECT_THROW(sph::write_json_file(bad + "/summary.json", nlohmann::json::object()), sph::Error);
  }
  remove_dir(dir);
}

TEST(IoCsvWriter, RoundTrip) {
  const std::string dir = fresh_dir("csv");
  if (rank() == 0) fs::create_directories(dir);
  MPI_Barrier(PETSC_COMM_WORLD);
  const std::string path = dir + "/timeseries.csv";
  const std::vector<std::string> columns = {"step", "t", "kinetic_energy", "error_l1"};
  const std::vector<std::vector<double>> rows = {
      {0, 0.0, 0.5, 0.0},
      {1, 1.0 / 3.0, 0.49999999999123, 1.234567890123456e-7},
      {2, 2.0 / 3.0, -6.02214076e23, 5e-324},
      {3, 1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()},
  };
  {
    sph::CsvWriter csv(path, columns);
    EXPECT_THROW(csv.row({1.0, 2.0}), sph::Error);  // wrong length: on every rank
    csv.row(rows[0]);
    csv.row(rows[1]);
    if (rank() == 0) {  // flushed after each row: readable before the writer is closed
      const std::string partial = slurp(path);
      EXPECT_EQ(count_occurrences(partial, "\n"), 3u) << partial;
    }
    csv.row(rows[2]);
    csv.row(rows[3]);
  }
  MPI_Barrier(PETSC_COMM_WORLD);
  if (rank() == 0) {
    std::ifstream in(path);
    std::string line;
    ASSERT_TRUE(std::getline(in, line));
    EXPECT_EQ(line, "step,t,kinetic_energy,error_l1");
    for (const auto& want : rows) {
      ASSERT_TRUE(std::getline(in, line));
      std::vector<double> got;
      std::stringstream ss(line);
      std::string cell;
      while (std::getline(ss, cell, ',')) got.push_back(std::strtod(cell.c_str(), nullptr));
      ASSERT_EQ(got.size(), want.size()) << line;
      for (std::size_t k = 0; k < want.size(); ++k) {
        if (std::isnan(want[k])) {
          EXPECT_TRUE(std::isnan(got[k])) << line;
        } else if (std::isinf(want[k])) {
          EXPECT_EQ(got[k], want[k]) << line;
        } else {
          EXPECT_NEAR(got[k], want[k], 1e-10 * std::abs(want[k])) << line;
          EXPECT_EQ(got[k], want[k]) << "round-trip exact: " << line;
        }
      }
    }
    EXPECT_FALSE(std::getline(in, line)) << "extra line: " << line;
  } else {
    // Only rank 0 writes; the others must not have touched the file (its header is rank 0's).
    SUCCEED();
  }
  remove_dir(dir);
}

TEST(IoJsonFile, RoundTripAndAtomicReplace) {
  const std::string dir = fresh_dir("json");
  if (rank() == 0) fs::create_directories(dir);
  MPI_Barrier(PETSC_COMM_WORLD);
  const std::string path = dir + "/summary.json";
  nlohmann::json j;
  j["case"] = "taylor_green";
  j["n_particles"] = 4096;
  j["dx"] = 1.0 / 64.0;
  j["errors"] = {{"velocity_l1", 1.25e-4}, {"diverged", std::numeric_limits<double>::quiet_NaN()}};
  j["models"] = nlohmann::json::array({"MorrisViscosity", "LindShifting"});
  j["bad_utf8"] = std::string("abc\xff");
  sph::write_json_file(path, nlohmann::json{{"old", true}});
  sph::write_json_file(path, j);  // replaces the old file
  MPI_Barrier(PETSC_COMM_WORLD);
  if (rank() == 0) {
    const std::string text = slurp(path);
    EXPECT_NE(text.find("\n  \"case\""), std::string::npos) << "indent 2:\n" << text;
    const nlohmann::json back = nlohmann::json::parse(text);
    EXPECT_FALSE(back.contains("old"));
    EXPECT_EQ(back["case"], "taylor_green");
    EXPECT_EQ(back["n_particles"], 4096);
    EXPECT_EQ(back["dx"].get<double>(), 1.0 / 64.0);
    EXPECT_EQ(back["errors"]["velocity_l1"].get<double>(), 1.25e-4);
    EXPECT_TRUE(back["errors"]["diverged"].is_null()) << "NaN is written as null";
    EXPECT_EQ(back["models"], j["models"]);
    EXPECT_TRUE(back["bad_utf8"].is_string());
    EXPECT_FALSE(fs::exists(path + ".tmp"));
  }
  remove_dir(dir);
}
