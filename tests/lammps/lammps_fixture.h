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

#include <stdexcept>
#include <string>
#include <vector>

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
