// A LAMMPS instance with the ActiveGrain plugin loaded, for in-process tests.
#pragma once

#include "exceptions.h"
#include "input.h"
#include "lammps.h"
#include "library.h"
#include "utils.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mpi.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

// This process's rank and the number of ranks in MPI_COMM_WORLD.
inline int mpi_rank()
{
  int me = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &me);
  return me;
}

inline int mpi_ranks()
{
  int n = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}

// Value of an equal-style expression in any LAMMPS instance (a serial reference's too); a LAMMPS
// error is a test failure and gives NaN.
inline double extracted(LAMMPS_NS::LAMMPS *lmp, const std::string &expr)
{
  lammps_command(lmp, ("variable agtest_value equal " + expr).c_str());
  auto *p = (double *) lammps_extract_variable(lmp, "agtest_value", nullptr);
  const double result = p ? *p : NAN;
  lammps_free(p);
  if (lammps_has_error(lmp)) {
    char message[2048] = "";
    lammps_get_last_error_message(lmp, message, sizeof(message));
    ADD_FAILURE() << expr << ": " << message;
  }
  return result;
}

class LammpsTest : public ::testing::Test {
 protected:
  LAMMPS_NS::LAMMPS *lmp = nullptr;

  void SetUp() override
  {
    std::vector<const char *> args = {"lmp", "-log", "none", "-nocite"};
    if (!verbose()) args.insert(args.end(), {"-screen", "none"});
    lmp = new LAMMPS_NS::LAMMPS((int) args.size(), const_cast<char **>(args.data()), MPI_COMM_WORLD);
    command(std::string("plugin load ") + ACTIVEGRAIN_PLUGIN_FILE);
  }
  void TearDown() override { delete lmp; }

  static bool verbose() { return getenv("ACTIVEGRAIN_TEST_VERBOSE") != nullptr; }

  // One command, or several separated by newlines.
  void command(const std::string &text) { lammps_commands_string(lmp, text.c_str()); rethrow(); }

  // The ERROR message the commands raise, or "" if they run through.
  std::string error_of(const std::string &text)
  {
    try {
      command(text);
    } catch (LAMMPS_NS::LAMMPSException &e) {
      return e.what();
    }
    return "";
  }

  // What `measure` returns (n values) from a LAMMPS of rank 0 alone (MPI_COMM_SELF), on every
  // rank: the serial reference of a test that then runs on all ranks. The fixture's instance is
  // closed meanwhile (plugins are registered once per process) and opened again afterwards.
  std::vector<double> serial_reference(int n, const std::function<std::vector<double>(LAMMPS_NS::LAMMPS *)> &measure)
  {
    std::vector<double> result(n, 0.0);
    TearDown();
    if (mpi_rank() == 0) {
      std::vector<const char *> args = {"lmp", "-log", "none", "-nocite", "-screen", "none"};
      auto alone = std::make_unique<LAMMPS_NS::LAMMPS>((int) args.size(), const_cast<char **>(args.data()),
                                                       MPI_COMM_SELF);
      lammps_command(alone.get(), "plugin load " ACTIVEGRAIN_PLUGIN_FILE);
      result = measure(alone.get());
      result.resize(n, 0.0);
    }
    SetUp();
    broadcast_from_rank0(result);
    return result;
  }

  // MPI_Bcast from rank 0, with the other ranks sleeping while they wait instead of polling:
  // where ranks outnumber the cores (8 ranks on 2 cores), polling ranks take most of the CPU
  // from rank 0's serial reference.
  static void broadcast_from_rank0(std::vector<double> &values)
  {
    MPI_Request request;
    MPI_Ibcast(values.data(), (int) values.size(), MPI_DOUBLE, 0, MPI_COMM_WORLD, &request);
    for (int done = 0;;) {
      MPI_Test(&request, &done, MPI_STATUS_IGNORE);
      if (done) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  }

  // Value of an equal-style expression, e.g. value("vx[3]") or value("v_rod_area").
  double value(const std::string &expr)
  {
    command("variable agtest_value equal " + expr);
    auto *p = (double *) lammps_extract_variable(lmp, "agtest_value", nullptr);
    if (!p) throw std::runtime_error("cannot evaluate " + expr);
    const double result = *p;
    lammps_free(p);
    return result;
  }

 private:
  // The library interface catches LAMMPS errors and keeps the message: turn it back into one.
  void rethrow()
  {
    if (lammps_has_error(lmp)) {
      char buf[2048];
      lammps_get_last_error_message(lmp, buf, sizeof(buf));
      throw LAMMPS_NS::LAMMPSException(buf);
    }
  }
};
