/* -*- c++ -*- ----------------------------------------------------------
   gran/hooke/history/cantact: LAMMPS's gran/hooke/history whose normal damping is set once per
   contact from a restitution coefficient e(v) read from a cantact e(V*) table (or a constant e);
   with `scatter SEED`, e at a probability drawn per contact from a table of samples' quantiles.

   A derived class of PairGranHookeHistory (LAMMPS 29 Sep 2021): the same force law, line for
   line, with gamma_n taken per contact from the contact's history instead of the pair_style's
   constant. See README.md beside this file.

   The same two files serve three ways of building it:
     - the add-on for Debian's packaged LAMMPS (build.sh; cantact_register.cpp registers it);
     - a plugin for a LAMMPS built with the PLUGIN package (cantact_plugin.cpp);
     - dropped into a LAMMPS source tree's src/ (the PairStyle line below registers it).
   SPDX-License-Identifier: GPL-2.0-only (it derives from LAMMPS 29 Sep 2021, GPL-2)
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(gran/hooke/history/cantact,PairGranHookeHistoryCantact);
// clang-format on
#else

#ifndef LMP_PAIR_GRAN_HOOKE_HISTORY_CANTACT_H
#define LMP_PAIR_GRAN_HOOKE_HISTORY_CANTACT_H

#include "pair_gran_hooke_history.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class PairGranHookeHistoryCantact : public PairGranHookeHistory {
 public:
  PairGranHookeHistoryCantact(class LAMMPS *);
  ~PairGranHookeHistoryCantact() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double single(int, int, int, int, double, double, double, double &) override;
  void transfer_history(double *, double *) override;
  void *extract(const char *, int &) override;

  // e <-> damping ratio zeta of a linear spring-dashpot (the .cpp states both laws): law 0
  // tension allowed (stock), law 1 force clipped at zero (limit_damping)
  static double zeta_of_e(double e, int law);
  static double e_of_zeta(double zeta, int law);
  static const char *zeta_relations();    // which implementation is compiled in

  // history values per contact: 0..2 the shear displacement (as stock), then:
  enum { H_SET = 3, H_E = 4, H_GAMMAN = 5, N_HISTORY = 6 };

 protected:
  // where e comes from, for one or more type pairs
  struct Source {
    int table;            // index in tables, or -1 for a constant e
    double e;             // the constant e (table < 0)
    double zeta;          // its damping ratio under this style's law (table < 0)
    double v_per_V_star;  // impact speed per unit V* (table >= 0): the table's or the user's
    int warned;           // a contact outside the table has been warned about (this rank)
  };
  struct Table;           // a loaded cantact table (opaque: cantact_table.h stays in the .cpp)
  std::vector<Table *> tables;
  std::vector<std::string> table_paths;
  std::vector<Source> sources;
  int **source_of;        // [itype][jtype]: index in sources, -1 when unset
  int default_source;     // from pair_style, -1 when none
  int gammat_from_gamman; // gamma_t given as NULL: 0.5 gamma_n of each contact
  int law;                // 0 tension allowed, 1 force clipped (limit_damping)
  long report_left;       // new contacts still to print (report N)
  int scatter;            // scatter SEED: e of each new contact at a drawn quantile p
  bigint scatter_seed;    // SEED (>= 0): Philox4x64-10's key word 0
  int outside_error;      // outside error: a contact outside its table's speeds is an error
  double contacts_set;    // contacts set up on this rank (pvector[0], summed by compute pair)
  double contacts_outside; // of which at a speed outside their table (pvector[1])

  int parse_source(int narg, char **arg, int &iarg, int &src, double &v_override, const char *cmd);
  int add_table(const std::string &path);
  int add_source(const Source &s);
  void check_source(const Source &s);
  // e at vn from the table's mean (p < 0) or at probability p in [0, 1] (its quantiles)
  double e_of_speed(const Source &s, double vn, double p, int &covered) const;
  // scatter: p in [0, 1) of the contact of atoms itag, jtag (either order) that starts at
  // step, a pure function of (scatter_seed, the tags, step)
  double scatter_p(tagint itag, tagint jtag, bigint step) const;
  // gamma_n (1/time, as stock: F_damp = meff gamma_n v_n) and e for a contact of atoms itag,
  // jtag that starts now with normal approach speed vn and effective mass meff (p: the drawn
  // probability with scatter, else -1); count: a new contact of compute() (counted, and warned
  // about or refused when outside its table), not single()
  void contact_damping(int itype, int jtype, tagint itag, tagint jtag, double vn, double meff,
                       double &e, double &p, double &gn, int count);
  void outside_table(Source &s, int itype, int jtype, double vn);
  void allocate_sources();
};

}    // namespace LAMMPS_NS

#endif
#endif
