/* ----------------------------------------------------------------------
   gran/hooke/history/cantact: see pair_gran_hooke_history_cantact.h and README.md.

   compute() and single() are PairGranHookeHistory's (LAMMPS 29 Sep 2021,
   src/GRANULAR/pair_gran_hooke_history.cpp; contributing authors of that code: Leo Silbert
   (SNL), Gary Grest (SNL); Copyright (2003) Sandia Corporation, GPL-2) with three changes:
     1. the history holds 6 values per contact instead of 3 (the shear, then a flag, e and
        gamma_n of the contact);
     2. at the first step of a contact (flag 0), e is looked up from the normal approach speed
        and gamma_n = 2 zeta(e) sqrt(kn / meff) is stored; every later step of the contact reads
        it back (LAMMPS's damping force is meff gamma_n v_n, so c_n = 2 zeta sqrt(meff kn));
     3. gamma_t given as NULL means 0.5 gamma_n of the contact (stock: 0.5 gamma_n).
   With `scatter SEED` (a table of samples), e in 2. is the table's e at the contact's speed and
   a probability p drawn once per contact (scatter_p: counter-based, the same on every rank);
   without it, the table's e (the mean of a table of samples), as before.
   Every floating-point expression of the force is otherwise the stock one, in the same order:
   with a constant e, and the stock style given this style's gamma_n, the trajectories are the
   same to the bit (test.sh checks it).
   SPDX-License-Identifier: GPL-2.0-only (derived from LAMMPS, GPL-2)
------------------------------------------------------------------------- */

#include "pair_gran_hooke_history_cantact.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix.h"
#include "fix_neigh_history.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

#include "cantact_table.h"

// scatter: Random123's counter-based Philox4x64-10 (header-only; Debian: librandom123-dev)
#include <Random123/philox.h>

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

using namespace LAMMPS_NS;

#ifndef MY_PI
#define CT_PI 3.14159265358979323846
#else
#define CT_PI MY_PI
#endif

struct PairGranHookeHistoryCantact::Table {
  ct_tab t;
};

/* ---------------------------------------------------------------------- */

PairGranHookeHistoryCantact::PairGranHookeHistoryCantact(LAMMPS *lmp) : PairGranHookeHistory(lmp)
{
  // the base constructor set size_history = 3; FixNeighHistory is created in
  // PairGranHookeHistory::init_style() with this size
  size_history = N_HISTORY;
  // e and gamma_n of a contact are the same seen from either atom (the shear changes sign)
  nondefault_history_transfer = 1;
  // the tables and settings are not written to restart files: give pair_style and pair_coeff
  // again after read_restart
  restartinfo = 0;

  source_of = nullptr;
  default_source = -1;
  gammat_from_gamman = 0;
  law = 0;
  report_left = 0;
  scatter = 0;
  scatter_seed = 0;
  outside_error = 0;
  gamman = 0.0;
  contacts_set = contacts_outside = 0.0;
  // compute pair's vector (summed over the ranks): contacts set up, of which outside their
  // table's speeds
  nextra = 2;
  pvector = new double[2];
  pvector[0] = pvector[1] = 0.0;
}

/* ---------------------------------------------------------------------- */

PairGranHookeHistoryCantact::~PairGranHookeHistoryCantact()
{
  if (copymode) return;
  for (Table *t : tables) {
    ct_tab_free(&t->t);
    delete t;
  }
  memory->destroy(source_of);
  delete[] pvector;
}

/* ----------------------------------------------------------------------
   e <-> zeta for a linear spring-dashpot (k, c = 2 zeta sqrt(m k)) hit at speed v from zero
   overlap (cantact_table.h states and derives both; the 29 Sep 2021 force is exactly this
   oscillator, stopped as the law says):
   law 0, tension allowed (stock gran/hooke/history): the contact ends at zero overlap after half
     a damped period, e = exp(-pi zeta / sqrt(1 - zeta^2)), zeta = -ln e / sqrt(pi^2 + ln^2 e)
     (e = 0 for zeta >= 1);
   law 1, force clipped at zero (limit_damping): the contact ends, in free flight, when
     k d + c d' = 0: ln e = -2 zeta h(zeta), h = acos(zeta) / sqrt(1 - zeta^2) (zeta < 1; this
     is e = exp(-x (pi - 2 atan x)), x = zeta / sqrt(1 - zeta^2)), 1 (zeta = 1, e = e^-2),
     acosh(zeta) / sqrt(zeta^2 - 1) (zeta > 1: overdamped, e < e^-2).
   The header's ct_tab_zeta_of_e / ct_tab_e_of_zeta are used when it has them (CT_TAB_PI marks
   that part of it); else the local copies below (the same relations; the inverse by bisection).
------------------------------------------------------------------------- */

#if defined(CT_TAB_PI) && !defined(CANTACT_LOCAL_ZETA)
#define CANTACT_ZETA_FROM_HEADER 1
#endif

#ifndef CANTACT_ZETA_FROM_HEADER
static double local_clipped_loss(double zeta)    // -ln e of law 1: 2 zeta h(zeta)
{
  double h;
  if (zeta < 1.0)
    h = acos(zeta) / sqrt((1.0 - zeta) * (1.0 + zeta));
  else if (zeta > 1.0)
    h = acosh(zeta) / (sqrt(zeta - 1.0) * sqrt(zeta + 1.0));
  else
    h = 1.0;
  return 2.0 * zeta * h;
}
#endif

const char *PairGranHookeHistoryCantact::zeta_relations()
{
#ifdef CANTACT_ZETA_FROM_HEADER
  return "cantact_table.h's ct_tab_zeta_of_e";
#else
  return "a local copy (this cantact_table.h has no ct_tab_zeta_of_e)";
#endif
}

double PairGranHookeHistoryCantact::e_of_zeta(double zeta, int law)
{
#ifdef CANTACT_ZETA_FROM_HEADER
  return ct_tab_e_of_zeta(zeta, law ? CT_TAB_CLIPPED : CT_TAB_TENSION);
#else
  if (!(zeta > 0.0)) return 1.0;
  if (law == 0) return zeta < 1.0 ? exp(-CT_PI * zeta / sqrt((1.0 - zeta) * (1.0 + zeta))) : 0.0;
  if (std::isinf(zeta)) return 0.0;
  return exp(-local_clipped_loss(zeta));
#endif
}

double PairGranHookeHistoryCantact::zeta_of_e(double e, int law)
{
#ifdef CANTACT_ZETA_FROM_HEADER
  return ct_tab_zeta_of_e(e, law ? CT_TAB_CLIPPED : CT_TAB_TENSION);
#else
  if (!(e < 1.0)) return 0.0;
  if (law == 0) {
    if (!(e > 0.0)) return 1.0;
    const double l = log(e);
    return -l / sqrt(CT_PI * CT_PI + l * l);
  }
  if (!(e > 0.0)) return INFINITY;    // refused at setup (check_source)
  // 2 zeta h(zeta) rises from 0 to infinity: bracket, then bisection to the last bit
  const double L = -log(e);
  double lo = 0.0, hi = 1.0;
  while (local_clipped_loss(hi) < L) {
    lo = hi;
    hi *= 2.0;
  }
  for (int it = 0; it < 2200; it++) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    if (local_clipped_loss(mid) < L)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
#endif
}

/* ----------------------------------------------------------------------
   e at normal approach speed vn (> 0 approaching) from one source: the table's e (its mean
   for a table of samples) when p < 0, else its e at probability p (ct_tab_eval_quantile);
   covered: 0 when the table does not know e there (ct_tab_covers: above V*_c and outside its
   nodes, where it gives its nearest end's e)
------------------------------------------------------------------------- */

double PairGranHookeHistoryCantact::e_of_speed(const Source &s, double vn, double p,
                                               int &covered) const
{
  covered = 1;
  if (s.table < 0) return s.e;
  const ct_tab &t = tables[s.table]->t;
  double V = vn / s.v_per_V_star;
  // a contact that starts without approaching (created overlapping): the low-speed limit
  if (!(V > 0.0))
    V = DBL_MIN;
  else
    covered = ct_tab_covers(&t, V);
  return p < 0.0 ? ct_tab_eval(&t, V) : ct_tab_eval_quantile(&t, V, p);
}

/* ----------------------------------------------------------------------
   scatter: the probability p in [0, 1) of the contact of atoms itag and jtag that starts at
   step. One Philox4x64-10 block (Random123), key (SEED, "scatter" in ASCII), counter (the
   smaller tag, the larger tag, step, 0); p = (its first 64-bit word >> 11) 2^-53. A pure
   function of (SEED, the pair, step): every rank that sets the contact up (both, for a pair
   across two ranks with newton off) draws the same p, on any number of ranks, in any order.
------------------------------------------------------------------------- */

double PairGranHookeHistoryCantact::scatter_p(tagint itag, tagint jtag, bigint step) const
{
  const uint64_t a = (uint64_t) (itag < jtag ? itag : jtag);
  const uint64_t b = (uint64_t) (itag < jtag ? jtag : itag);
  const philox4x64_key_t key = {{(uint64_t) scatter_seed, UINT64_C(0x73636174746572)}};
  const philox4x64_ctr_t ctr = {{a, b, (uint64_t) step, 0}};
  const philox4x64_ctr_t r = philox4x64(ctr, key);
  return ldexp((double) (r.v[0] >> 11), -53);
}

void PairGranHookeHistoryCantact::contact_damping(int itype, int jtype, tagint itag,
                                                  tagint jtag, double vn, double meff, double &e,
                                                  double &p, double &gn, int count)
{
  Source &s = sources[source_of[itype][jtype]];
  double zeta;
  p = -1.0;
  if (s.table < 0) {
    e = s.e;    // with scatter: refused at setup (init_style)
    zeta = s.zeta;
  } else {
    int covered;
    if (scatter) p = scatter_p(itag, jtag, update->ntimestep);
    e = e_of_speed(s, vn, p, covered);
    zeta = zeta_of_e(e, law);
    if (count && !covered) outside_table(s, itype, jtype, vn);
  }
  if (count) contacts_set += 1.0;
  gn = 2.0 * zeta * sqrt(kn / meff);
}

/* ----------------------------------------------------------------------
   a contact that starts at a speed its table does not cover: counted; an error with
   `outside error`, else a warning, once per source on each rank (LAMMPS prints what rank 0,
   or a rank with a screen or log, warns; the count of every rank is in compute pair's vector)
------------------------------------------------------------------------- */

void PairGranHookeHistoryCantact::outside_table(Source &s, int itype, int jtype, double vn)
{
  contacts_outside += 1.0;
  const ct_tab &t = tables[s.table]->t;
  const double S = s.v_per_V_star;
  const std::string what = fmt::format(
      "gran/hooke/history/cantact: a contact of types {} {} starts at v_n = {:.6g} (V* = {:.6g}), "
      "outside table {}: it knows e for v_n <= {:.6g} (e = 1) and {:.6g} .. {:.6g}",
      itype, jtype, vn, vn / S, table_paths[s.table], t.V_star_crit * S, t.V_star[0] * S,
      t.V_star[t.n - 1] * S);
  if (outside_error)
    error->one(FLERR, "{} (outside error)", what);
  if (!s.warned) {
    s.warned = 1;
    error->warning(FLERR,
                   "{}: e of its nearest end used; warned once per table and rank, every such "
                   "contact counted (compute pair: its vector's second value)",
                   what);
  }
}

/* ---------------------------------------------------------------------- */

void PairGranHookeHistoryCantact::compute(int eflag, int vflag)
{
  int i, j, ii, jj, inum, jnum;
  double xtmp, ytmp, ztmp, delx, dely, delz, fx, fy, fz;
  double radi, radj, radsum, rsq, r, rinv, rsqinv;
  double vr1, vr2, vr3, vnnr, vn1, vn2, vn3, vt1, vt2, vt3;
  double wr1, wr2, wr3;
  double vtr1, vtr2, vtr3, vrel;
  double mi, mj, meff, damp, ccel, tor1, tor2, tor3;
  double fn, fs, fs1, fs2, fs3;
  double shrmag, rsht;
  int *ilist, *jlist, *numneigh, **firstneigh;
  int *touch, **firsttouch;
  double *shear, *allshear, **firstshear;
  double gn, gt;

  ev_init(eflag, vflag);

  int shearupdate = 1;
  if (update->setupflag) shearupdate = 0;

  if (fix_rigid && neighbor->ago == 0) {
    int tmp;
    int *body = (int *) fix_rigid->extract("body", tmp);
    double *mass_body = (double *) fix_rigid->extract("masstotal", tmp);
    if (atom->nmax > nmax) {
      memory->destroy(mass_rigid);
      nmax = atom->nmax;
      memory->create(mass_rigid, nmax, "pair:mass_rigid");
    }
    int nlocal = atom->nlocal;
    for (i = 0; i < nlocal; i++)
      if (body[i] >= 0)
        mass_rigid[i] = mass_body[body[i]];
      else
        mass_rigid[i] = 0.0;
    comm->forward_comm_pair(this);
  }

  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  double **omega = atom->omega;
  double **torque = atom->torque;
  double *radius = atom->radius;
  double *rmass = atom->rmass;
  int *mask = atom->mask;
  int *type = atom->type;
  int nlocal = atom->nlocal;
  int newton_pair = force->newton_pair;

  inum = list->inum;
  ilist = list->ilist;
  numneigh = list->numneigh;
  firstneigh = list->firstneigh;
  firsttouch = fix_history->firstflag;
  firstshear = fix_history->firstvalue;

  for (ii = 0; ii < inum; ii++) {
    i = ilist[ii];
    xtmp = x[i][0];
    ytmp = x[i][1];
    ztmp = x[i][2];
    radi = radius[i];
    touch = firsttouch[i];
    allshear = firstshear[i];
    jlist = firstneigh[i];
    jnum = numneigh[i];

    for (jj = 0; jj < jnum; jj++) {
      j = jlist[jj];
      j &= NEIGHMASK;

      delx = xtmp - x[j][0];
      dely = ytmp - x[j][1];
      delz = ztmp - x[j][2];
      rsq = delx * delx + dely * dely + delz * delz;
      radj = radius[j];
      radsum = radi + radj;

      if (rsq >= radsum * radsum) {

        // unset non-touching neighbors: the next touch is a new contact

        touch[jj] = 0;
        shear = &allshear[N_HISTORY * jj];
        for (int m = 0; m < N_HISTORY; m++) shear[m] = 0.0;

      } else {
        r = sqrt(rsq);
        rinv = 1.0 / r;
        rsqinv = 1.0 / rsq;

        vr1 = v[i][0] - v[j][0];
        vr2 = v[i][1] - v[j][1];
        vr3 = v[i][2] - v[j][2];

        vnnr = vr1 * delx + vr2 * dely + vr3 * delz;
        vn1 = delx * vnnr * rsqinv;
        vn2 = dely * vnnr * rsqinv;
        vn3 = delz * vnnr * rsqinv;

        vt1 = vr1 - vn1;
        vt2 = vr2 - vn2;
        vt3 = vr3 - vn3;

        wr1 = (radi * omega[i][0] + radj * omega[j][0]) * rinv;
        wr2 = (radi * omega[i][1] + radj * omega[j][1]) * rinv;
        wr3 = (radi * omega[i][2] + radj * omega[j][2]) * rinv;

        mi = rmass[i];
        mj = rmass[j];
        if (fix_rigid) {
          if (mass_rigid[i] > 0.0) mi = mass_rigid[i];
          if (mass_rigid[j] > 0.0) mj = mass_rigid[j];
        }

        meff = mi * mj / (mi + mj);
        if (mask[i] & freeze_group_bit) meff = mj;
        if (mask[j] & freeze_group_bit) meff = mi;

        // the contact's damping: set at its first step from the normal approach speed
        // -vnnr / r (vnnr < 0 approaching), kept in its history until it ends

        shear = &allshear[N_HISTORY * jj];
        if (shear[H_SET] == 0.0) {
          double e, p;
          // counted once: a pair across two ranks with newton off is set up on both
          const int count = newton_pair || j < nlocal || atom->tag[i] < atom->tag[j];
          contact_damping(type[i], type[j], atom->tag[i], atom->tag[j], -vnnr * rinv, meff, e,
                          p, gn, count);
          shear[H_SET] = 1.0;
          shear[H_E] = e;
          shear[H_GAMMAN] = gn;
          if (report_left > 0 && comm->me == 0) {
            report_left--;
            std::string line = fmt::format(
                "cantact: contact {} {} step {} v_n {:.17g} e {:.17g} zeta {:.17g} meff "
                "{:.17g} gamma_n {:.17g}",
                atom->tag[i], atom->tag[j], update->ntimestep, -vnnr * rinv, e,
                zeta_of_e(e, law), meff, gn);
            line += scatter ? fmt::format(" p {:.17g}\n", p) : std::string("\n");
            if (screen) fputs(line.c_str(), screen);
            if (logfile) fputs(line.c_str(), logfile);
          }
        }
        gn = shear[H_GAMMAN];
        gt = gammat_from_gamman ? 0.5 * gn : gammat;
        if (dampflag == 0) gt = 0.0;

        // normal forces = Hookian contact + normal velocity damping

        damp = meff * gn * vnnr * rsqinv;
        ccel = kn * (radsum - r) * rinv - damp;
        if (limit_damping && (ccel < 0.0)) ccel = 0.0;

        vtr1 = vt1 - (delz * wr2 - dely * wr3);
        vtr2 = vt2 - (delx * wr3 - delz * wr1);
        vtr3 = vt3 - (dely * wr1 - delx * wr2);
        vrel = vtr1 * vtr1 + vtr2 * vtr2 + vtr3 * vtr3;
        vrel = sqrt(vrel);

        // shear history effects

        touch[jj] = 1;

        if (shearupdate) {
          shear[0] += vtr1 * dt;
          shear[1] += vtr2 * dt;
          shear[2] += vtr3 * dt;
        }
        shrmag = sqrt(shear[0] * shear[0] + shear[1] * shear[1] + shear[2] * shear[2]);

        rsht = shear[0] * delx + shear[1] * dely + shear[2] * delz;
        rsht *= rsqinv;
        if (shearupdate) {
          shear[0] -= rsht * delx;
          shear[1] -= rsht * dely;
          shear[2] -= rsht * delz;
        }

        fs1 = -(kt * shear[0] + meff * gt * vtr1);
        fs2 = -(kt * shear[1] + meff * gt * vtr2);
        fs3 = -(kt * shear[2] + meff * gt * vtr3);

        fs = sqrt(fs1 * fs1 + fs2 * fs2 + fs3 * fs3);
        fn = xmu * fabs(ccel * r);

        if (fs > fn) {
          if (shrmag != 0.0) {
            shear[0] = (fn / fs) * (shear[0] + meff * gt * vtr1 / kt) - meff * gt * vtr1 / kt;
            shear[1] = (fn / fs) * (shear[1] + meff * gt * vtr2 / kt) - meff * gt * vtr2 / kt;
            shear[2] = (fn / fs) * (shear[2] + meff * gt * vtr3 / kt) - meff * gt * vtr3 / kt;
            fs1 *= fn / fs;
            fs2 *= fn / fs;
            fs3 *= fn / fs;
          } else
            fs1 = fs2 = fs3 = 0.0;
        }

        fx = delx * ccel + fs1;
        fy = dely * ccel + fs2;
        fz = delz * ccel + fs3;
        f[i][0] += fx;
        f[i][1] += fy;
        f[i][2] += fz;

        tor1 = rinv * (dely * fs3 - delz * fs2);
        tor2 = rinv * (delz * fs1 - delx * fs3);
        tor3 = rinv * (delx * fs2 - dely * fs1);
        torque[i][0] -= radi * tor1;
        torque[i][1] -= radi * tor2;
        torque[i][2] -= radi * tor3;

        if (newton_pair || j < nlocal) {
          f[j][0] -= fx;
          f[j][1] -= fy;
          f[j][2] -= fz;
          torque[j][0] -= radj * tor1;
          torque[j][1] -= radj * tor2;
          torque[j][2] -= radj * tor3;
        }

        if (evflag) ev_tally_xyz(i, j, nlocal, newton_pair, 0.0, 0.0, fx, fy, fz, delx, dely, delz);
      }
    }
  }

  if (vflag_fdotr) virial_fdotr_compute();
  pvector[0] = contacts_set;
  pvector[1] = contacts_outside;
}

/* ----------------------------------------------------------------------
   history seen from the other atom: shear negated (the stock rule), e and gamma_n kept
------------------------------------------------------------------------- */

void PairGranHookeHistoryCantact::transfer_history(double *source, double *target)
{
  for (int m = 0; m < 3; m++) target[m] = -source[m];
  for (int m = 3; m < N_HISTORY; m++) target[m] = source[m];
}

/* ----------------------------------------------------------------------
   pair_style gran/hooke/history/cantact Kn Kt gamma_t xmu dampflag keyword value ...
     keywords: table FILE | e E   (where e comes from: required here or in every pair_coeff)
               v_per_V_star S     (impact speed per unit V*: overrides the table's)
               limit_damping      (as stock; damping from e by the force-clipped relation)
               report N           (print the first N new contacts seen by proc 0)
               outside warn|error (a contact at a speed outside its table: the nearest end's
                                   e and a warning once per table, or an error)
               scatter SEED       (SEED >= 0: each new contact takes e at a probability p
                                   drawn from (SEED, its atoms' ids, its first step) from its
                                   table's quantile columns, not the mean; tables of samples
                                   only, for every type pair)
------------------------------------------------------------------------- */

void PairGranHookeHistoryCantact::settings(int narg, char **arg)
{
  if (narg < 5)
    error->all(FLERR,
               "Illegal pair_style gran/hooke/history/cantact command: Kn Kt gamma_t xmu "
               "dampflag [table FILE | e E] [v_per_V_star S] [limit_damping] [report N] "
               "[outside warn|error] [scatter SEED]");

  kn = utils::numeric(FLERR, arg[0], false, lmp);
  if (strcmp(arg[1], "NULL") == 0)
    kt = kn * 2.0 / 7.0;
  else
    kt = utils::numeric(FLERR, arg[1], false, lmp);

  gamman = 0.0;    // per contact: not used
  gammat_from_gamman = 0;
  gammat = 0.0;
  if (strcmp(arg[2], "NULL") == 0)
    gammat_from_gamman = 1;
  else
    gammat = utils::numeric(FLERR, arg[2], false, lmp);

  xmu = utils::numeric(FLERR, arg[3], false, lmp);
  dampflag = utils::inumeric(FLERR, arg[4], false, lmp);
  if (dampflag == 0) {
    gammat = 0.0;
    gammat_from_gamman = 0;
  }

  if (kn < 0.0 || kt < 0.0 || gammat < 0.0 || xmu < 0.0 || xmu > 10000.0 || dampflag < 0 ||
      dampflag > 1)
    error->all(FLERR, "Illegal pair_style gran/hooke/history/cantact command");

  // the keywords; limit_damping and scatter first, as checking a source depends on them (the
  // law: the source's zeta; scatter: the least e of the quantile columns)
  limit_damping = 0;
  report_left = 0;
  outside_error = 0;
  scatter = 0;
  scatter_seed = 0;
  for (int iarg = 5; iarg < narg; iarg++) {
    if (strcmp(arg[iarg], "limit_damping") == 0) limit_damping = 1;
    if (strcmp(arg[iarg], "scatter") == 0) scatter = 1;
  }
  law = limit_damping ? 1 : 0;

  int src = -1;
  double v_override = -1.0;
  int iarg = 5;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "limit_damping") == 0) {
      iarg++;
    } else if (strcmp(arg[iarg], "report") == 0) {
      if (iarg + 1 >= narg) error->all(FLERR, "pair_style gran/hooke/history/cantact: report N");
      report_left = utils::bnumeric(FLERR, arg[iarg + 1], false, lmp);
      iarg += 2;
    } else if (strcmp(arg[iarg], "outside") == 0) {
      if (iarg + 1 >= narg || (strcmp(arg[iarg + 1], "warn") && strcmp(arg[iarg + 1], "error")))
        error->all(FLERR, "pair_style gran/hooke/history/cantact: outside warn | outside error");
      outside_error = strcmp(arg[iarg + 1], "error") == 0;
      iarg += 2;
    } else if (strcmp(arg[iarg], "scatter") == 0) {
      if (iarg + 1 >= narg)
        error->all(FLERR, "pair_style gran/hooke/history/cantact: scatter SEED (an integer >= 0)");
      scatter_seed = utils::bnumeric(FLERR, arg[iarg + 1], false, lmp);
      if (scatter_seed < 0)
        error->all(FLERR, "pair_style gran/hooke/history/cantact: scatter {}: SEED must be >= 0",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (!parse_source(narg, arg, iarg, src, v_override, "pair_style")) {
      error->all(FLERR, "Illegal pair_style gran/hooke/history/cantact keyword: {}", arg[iarg]);
    }
  }
  if (v_override > 0.0 && src >= 0 && sources[src].table < 0)
    error->all(FLERR, "pair_style gran/hooke/history/cantact: v_per_V_star needs a table");
  // src is the source this command's `table` made: its v_per_V_star is overridden in place (a
  // copy would leave the table's own, maybe NaN, to be refused below)
  if (src >= 0 && v_override > 0.0) sources[src].v_per_V_star = v_override;
  default_source = src;

  // a pair_style command given again: the type pairs set by pair_coeff keep their own source,
  // recomputed below for the (maybe new) law
  for (Source &s : sources)
    if (s.table < 0) s.zeta = zeta_of_e(s.e, law);
  for (const Source &s : sources) check_source(s);
  if (comm->me == 0)
    utils::logmesg(lmp, "gran/hooke/history/cantact: e -> damping by the {} relation, from {}\n",
                   law ? "force-clipped (limit_damping)" : "tension-allowed (stock)",
                   zeta_relations());
  if (scatter && comm->me == 0)
    utils::logmesg(lmp,
                   "gran/hooke/history/cantact: scatter {}: each new contact takes e at its "
                   "speed and a probability p in [0, 1) from its table's quantile columns; p is "
                   "Philox4x64-10 of key ({}, 0x73636174746572), counter (smaller id, larger id, "
                   "first step, 0)\n",
                   scatter_seed, scatter_seed);
}

/* ----------------------------------------------------------------------
   table FILE | e E | v_per_V_star S at arg[iarg]: 1 and iarg advanced, or 0 when not one of
   them. src is set to the source (a table or a constant); v_override to S.
------------------------------------------------------------------------- */

int PairGranHookeHistoryCantact::parse_source(int narg, char **arg, int &iarg, int &src,
                                              double &v_override, const char *cmd)
{
  if (strcmp(arg[iarg], "table") == 0) {
    if (iarg + 1 >= narg) error->all(FLERR, "{} gran/hooke/history/cantact: table FILE", cmd);
    Source s;
    s.table = add_table(arg[iarg + 1]);
    s.e = 0.0;
    s.zeta = 0.0;
    s.v_per_V_star = tables[s.table]->t.v_per_V_star;
    s.warned = 0;
    src = add_source(s);
    iarg += 2;
    return 1;
  }
  if (strcmp(arg[iarg], "e") == 0) {
    if (iarg + 1 >= narg) error->all(FLERR, "{} gran/hooke/history/cantact: e E", cmd);
    Source s;
    s.table = -1;
    s.e = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
    if (!(s.e >= 0.0 && s.e <= 1.0))
      error->all(FLERR, "{} gran/hooke/history/cantact: e {} is not in [0, 1]", cmd, s.e);
    s.zeta = zeta_of_e(s.e, law);
    s.v_per_V_star = 1.0;
    s.warned = 0;
    check_source(s);
    src = add_source(s);
    iarg += 2;
    return 1;
  }
  if (strcmp(arg[iarg], "v_per_V_star") == 0) {
    if (iarg + 1 >= narg) error->all(FLERR, "{} gran/hooke/history/cantact: v_per_V_star S", cmd);
    v_override = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
    if (!(v_override > 0.0 && std::isfinite(v_override)))
      error->all(FLERR, "{} gran/hooke/history/cantact: v_per_V_star must be > 0", cmd);
    iarg += 2;
    return 1;
  }
  return 0;
}

/* ----------------------------------------------------------------------
   load a table once per path: proc 0 reads it, every proc gets a copy
------------------------------------------------------------------------- */

int PairGranHookeHistoryCantact::add_table(const std::string &path)
{
  for (size_t k = 0; k < table_paths.size(); k++)
    if (table_paths[k] == path) return (int) k;

  Table *tab = new Table;
  ct_tab &t = tab->t;
  // every pointer null: the ranks that do not read the file fill in only what they are sent,
  // and ct_tab_free frees them all (the quantile columns too, absent from most tables)
  memset(&t, 0, sizeof t);
  char err[1024] = "";
  int status = 0;
  if (comm->me == 0) status = ct_tab_load(&t, path.c_str(), err, sizeof err) ? 1 : 0;
  MPI_Bcast(&status, 1, MPI_INT, 0, world);
  if (status) {
    delete tab;
    error->all(FLERR, "gran/hooke/history/cantact: {}", err);
  }
  bigint n = comm->me == 0 ? (bigint) t.n : 0, nq = comm->me == 0 ? (bigint) t.nq : 0;
  MPI_Bcast(&n, 1, MPI_LMP_BIGINT, 0, world);
  MPI_Bcast(&nq, 1, MPI_LMP_BIGINT, 0, world);
  double head[5] = {(double) t.rule, t.V_star_crit, t.tolerance, t.worst_error, t.v_per_V_star};
  MPI_Bcast(head, 5, MPI_DOUBLE, 0, world);
  if (comm->me != 0) {
    t.n = (size_t) n;
    t.rule = (int) head[0];
    t.V_star_crit = head[1];
    t.tolerance = head[2];
    t.worst_error = head[3];
    t.v_per_V_star = head[4];
    t.worst_V_star = NAN;
    t.V_star = (double *) malloc(t.n * sizeof(double));
    t.ln_V_star = (double *) malloc(t.n * sizeof(double));
    t.e = (double *) malloc(t.n * sizeof(double));
    t.slope = (double *) malloc(t.n * sizeof(double));
    if (!t.V_star || !t.ln_V_star || !t.e || !t.slope)
      error->one(FLERR, "gran/hooke/history/cantact: out of memory for table {}", path);
    t.nq = (size_t) nq;
    if (nq) {    // a table of samples: its quantile columns, laid out as ct_tab_read leaves them
      t.p = (double *) malloc(t.nq * sizeof(double));
      t.e_q = (double *) malloc(t.n * t.nq * sizeof(double));
      t.slope_q = (double *) malloc(t.n * t.nq * sizeof(double));
      if (!t.p || !t.e_q || !t.slope_q)
        error->one(FLERR, "gran/hooke/history/cantact: out of memory for table {}", path);
    }
  }
  MPI_Bcast(t.V_star, (int) n, MPI_DOUBLE, 0, world);
  MPI_Bcast(t.ln_V_star, (int) n, MPI_DOUBLE, 0, world);
  MPI_Bcast(t.e, (int) n, MPI_DOUBLE, 0, world);
  MPI_Bcast(t.slope, (int) n, MPI_DOUBLE, 0, world);
  if (nq) {
    MPI_Bcast(t.p, (int) nq, MPI_DOUBLE, 0, world);
    MPI_Bcast(t.e_q, (int) (n * nq), MPI_DOUBLE, 0, world);
    MPI_Bcast(t.slope_q, (int) (n * nq), MPI_DOUBLE, 0, world);
  }

  tables.push_back(tab);
  table_paths.push_back(path);
  if (comm->me == 0)
    utils::logmesg(lmp,
                   "gran/hooke/history/cantact: table {}: {} nodes on V* {:.6g} .. {:.6g}, e "
                   "{:.6g} .. 1, v_per_V_star {:.17g}{}\n",
                   path, t.n, t.V_star[0], t.V_star[t.n - 1], t.e[t.n - 1], t.v_per_V_star,
                   t.nq ? fmt::format(", {} quantile columns p = {:.6g} .. {:.6g}", t.nq, t.p[0],
                                      t.p[t.nq - 1])
                        : std::string(", no quantile columns"));
  return (int) tables.size() - 1;
}

int PairGranHookeHistoryCantact::add_source(const Source &s)
{
  sources.push_back(s);
  return (int) sources.size() - 1;
}

/* ----------------------------------------------------------------------
   refuse what the damping cannot give: with limit_damping (force clipped at zero) e = 0 needs
   an infinite gamma_n (every finite one rebounds: e ~ 1 / (2 zeta)^2)
------------------------------------------------------------------------- */

void PairGranHookeHistoryCantact::check_source(const Source &s)
{
  double emin;
  if (s.table < 0)
    emin = s.e;
  else {
    const ct_tab &t = tables[s.table]->t;
    if (!(s.v_per_V_star > 0.0))
      error->all(FLERR,
                 "gran/hooke/history/cantact: table {} has no v_per_V_star (give [impact] mass in "
                 "the scene, or v_per_V_star S here)",
                 table_paths[s.table]);
    emin = 1.0;
    for (size_t k = 0; k < t.n; k++)
      if (t.e[k] < emin) emin = t.e[k];    // both rules keep e within its nodes
    if (scatter)    // and so the quantile columns within theirs (and p between two columns)
      for (size_t k = 0; k < t.n * t.nq; k++)
        if (t.e_q[k] < emin) emin = t.e_q[k];
    if (comm->me == 0)
      utils::logmesg(lmp,
                     "gran/hooke/history/cantact: table {} with v_per_V_star {:.17g} knows e for "
                     "v_n <= {:.6g} (e = 1) and {:.6g} .. {:.6g}; outside: its nearest end's e "
                     "and {}\n",
                     table_paths[s.table], s.v_per_V_star, t.V_star_crit * s.v_per_V_star,
                     t.V_star[0] * s.v_per_V_star, t.V_star[t.n - 1] * s.v_per_V_star,
                     outside_error ? "an error (outside error)" : "a warning");
  }
  if (law == 1 && !(emin > 0.0))
    error->all(FLERR,
               "gran/hooke/history/cantact: e = 0 with limit_damping (force clipped at zero) "
               "needs an infinite damping; every finite one rebounds");
}

void PairGranHookeHistoryCantact::allocate_sources()
{
  if (source_of) return;
  const int n = atom->ntypes;
  memory->create(source_of, n + 1, n + 1, "pair:source_of");
  for (int i = 0; i <= n; i++)
    for (int j = 0; j <= n; j++) source_of[i][j] = -1;
}

/* ----------------------------------------------------------------------
   pair_coeff I J [table FILE | e E] [v_per_V_star S]
------------------------------------------------------------------------- */

void PairGranHookeHistoryCantact::coeff(int narg, char **arg)
{
  if (narg < 2) error->all(FLERR, "Incorrect args for pair coefficients");
  int src = default_source;
  double v_override = -1.0;
  int iarg = 2;
  while (iarg < narg)
    if (!parse_source(narg, arg, iarg, src, v_override, "pair_coeff"))
      error->all(FLERR, "Incorrect args for pair coefficients: {}", arg[iarg]);
  if (src < 0)
    error->all(FLERR,
               "pair_coeff gran/hooke/history/cantact: no e for these types (table FILE or e E, "
               "here or in pair_style)");
  if (v_override > 0.0) {
    if (sources[src].table < 0)
      error->all(FLERR, "pair_coeff gran/hooke/history/cantact: v_per_V_star needs a table");
    Source s = sources[src];
    s.v_per_V_star = v_override;
    check_source(s);
    src = add_source(s);
  } else if (src != default_source) {
    check_source(sources[src]);    // a table of its own: it needs its v_per_V_star too
  }

  PairGranHookeHistory::coeff(2, arg);    // allocate(), setflag
  allocate_sources();
  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);
  for (int i = ilo; i <= ihi; i++)
    for (int j = MAX(jlo, i); j <= jhi; j++) source_of[i][j] = source_of[j][i] = src;
}

/* ---------------------------------------------------------------------- */

void PairGranHookeHistoryCantact::init_style()
{
  PairGranHookeHistory::init_style();
  if (!source_of) error->all(FLERR, "gran/hooke/history/cantact: no pair_coeff given");
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++)
      if (setflag[i][j] && source_of[i][j] < 0)
        error->all(FLERR, "gran/hooke/history/cantact: no e for types {} {}", i, j);
  // scatter draws from quantile columns: every type pair needs a table of samples
  for (int i = 1; scatter && i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      if (!setflag[i][j]) continue;
      const Source &s = sources[source_of[i][j]];
      if (s.table < 0)
        error->all(FLERR,
                   "gran/hooke/history/cantact: scatter needs a table of samples, but types {} {} "
                   "have the constant e {}",
                   i, j, s.e);
      if (!tables[s.table]->t.nq)
        error->all(FLERR,
                   "gran/hooke/history/cantact: scatter needs a table of samples, but table {} "
                   "(types {} {}) has no quantile columns (write it from a scene with [body] "
                   "landings or [ensemble] realisations)",
                   table_paths[s.table], i, j);
    }
}

/* ----------------------------------------------------------------------
   the stock single() with the contact's gamma_n (for compute pair/local)
------------------------------------------------------------------------- */

double PairGranHookeHistoryCantact::single(int i, int j, int itype, int jtype, double rsq,
                                           double /*factor_coul*/, double /*factor_lj*/,
                                           double &fforce)
{
  double radi, radj, radsum;
  double r, rinv, rsqinv, delx, dely, delz;
  double vr1, vr2, vr3, vnnr, vn1, vn2, vn3, vt1, vt2, vt3, wr1, wr2, wr3;
  double mi, mj, meff, damp, ccel;
  double vtr1, vtr2, vtr3, vrel, shrmag, rsht;
  double fs1, fs2, fs3, fs, fn;

  double *radius = atom->radius;
  radi = radius[i];
  radj = radius[j];
  radsum = radi + radj;

  if (rsq >= radsum * radsum) {
    fforce = 0.0;
    for (int m = 0; m < single_extra; m++) svector[m] = 0.0;
    return 0.0;
  }

  r = sqrt(rsq);
  rinv = 1.0 / r;
  rsqinv = 1.0 / rsq;

  double **v = atom->v;
  vr1 = v[i][0] - v[j][0];
  vr2 = v[i][1] - v[j][1];
  vr3 = v[i][2] - v[j][2];

  double **x = atom->x;
  delx = x[i][0] - x[j][0];
  dely = x[i][1] - x[j][1];
  delz = x[i][2] - x[j][2];

  vnnr = vr1 * delx + vr2 * dely + vr3 * delz;
  vn1 = delx * vnnr * rsqinv;
  vn2 = dely * vnnr * rsqinv;
  vn3 = delz * vnnr * rsqinv;

  vt1 = vr1 - vn1;
  vt2 = vr2 - vn2;
  vt3 = vr3 - vn3;

  double **omega = atom->omega;
  wr1 = (radi * omega[i][0] + radj * omega[j][0]) * rinv;
  wr2 = (radi * omega[i][1] + radj * omega[j][1]) * rinv;
  wr3 = (radi * omega[i][2] + radj * omega[j][2]) * rinv;

  double *rmass = atom->rmass;
  int *mask = atom->mask;

  mi = rmass[i];
  mj = rmass[j];
  if (fix_rigid) {
    if (mass_rigid[i] > 0.0) mi = mass_rigid[i];
    if (mass_rigid[j] > 0.0) mj = mass_rigid[j];
  }

  meff = mi * mj / (mi + mj);
  if (mask[i] & freeze_group_bit) meff = mj;
  if (mask[j] & freeze_group_bit) meff = mi;

  int jnum = list->numneigh[i];
  int *jlist = list->firstneigh[i];
  double *allshear = fix_history->firstvalue[i];

  for (int jj = 0; jj < jnum; jj++) {
    neighprev++;
    if (neighprev >= jnum) neighprev = 0;
    if (jlist[neighprev] == j) break;
  }

  double *shear = &allshear[N_HISTORY * neighprev];
  double gn, e, p;
  if (shear[H_SET] != 0.0)
    gn = shear[H_GAMMAN];
  else
    contact_damping(itype, jtype, atom->tag[i], atom->tag[j], -vnnr * rinv, meff, e, p, gn, 0);
  double gt = gammat_from_gamman ? 0.5 * gn : gammat;
  if (dampflag == 0) gt = 0.0;

  damp = meff * gn * vnnr * rsqinv;
  ccel = kn * (radsum - r) * rinv - damp;
  if (limit_damping && (ccel < 0.0)) ccel = 0.0;

  vtr1 = vt1 - (delz * wr2 - dely * wr3);
  vtr2 = vt2 - (delx * wr3 - delz * wr1);
  vtr3 = vt3 - (dely * wr1 - delx * wr2);
  vrel = vtr1 * vtr1 + vtr2 * vtr2 + vtr3 * vtr3;
  vrel = sqrt(vrel);

  shrmag = sqrt(shear[0] * shear[0] + shear[1] * shear[1] + shear[2] * shear[2]);

  rsht = shear[0] * delx + shear[1] * dely + shear[2] * delz;
  rsht *= rsqinv;

  fs1 = -(kt * shear[0] + meff * gt * vtr1);
  fs2 = -(kt * shear[1] + meff * gt * vtr2);
  fs3 = -(kt * shear[2] + meff * gt * vtr3);

  fs = sqrt(fs1 * fs1 + fs2 * fs2 + fs3 * fs3);
  fn = xmu * fabs(ccel * r);

  if (fs > fn) {
    if (shrmag != 0.0) {
      fs1 *= fn / fs;
      fs2 *= fn / fs;
      fs3 *= fn / fs;
      fs *= fn / fs;
    } else
      fs1 = fs2 = fs3 = fs = 0.0;
  }

  fforce = ccel;

  svector[0] = fs1;
  svector[1] = fs2;
  svector[2] = fs3;
  svector[3] = fs;
  svector[4] = vn1;
  svector[5] = vn2;
  svector[6] = vn3;
  svector[7] = vt1;
  svector[8] = vt2;
  svector[9] = vt3;

  return 0.0;
}

/* ----------------------------------------------------------------------
   extract("limit_damping"), extract("kn"): for scripts that check the setup
------------------------------------------------------------------------- */

void *PairGranHookeHistoryCantact::extract(const char *str, int &dim)
{
  dim = 0;
  if (strcmp(str, "limit_damping") == 0) return (void *) &limit_damping;
  if (strcmp(str, "kn") == 0) return (void *) &kn;
  return nullptr;
}
