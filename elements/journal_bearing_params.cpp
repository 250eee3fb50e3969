// The journal-bearing element's parameter table (names, units, ranges, choices,
// the element's documentation): see journal_bearing.h and
// docs/elements-journal-bearing.md.
#include "elements/journal_bearing.h"
#include "elements/param_binding.h"

namespace evas {

ElementType journal_bearing_element_type() {
  ElementType t;
  t.type = "journal-bearing";
  t.doc =
      "Hydrodynamic journal bearing, short-bearing (Ocvirk) theory with the pi-film condition "
      "(paper Eq. 3, Figs. 5-6). Marker 1 = bearing (its z axis is the bearing axis, x/y span "
      "the bearing plane), marker 2 = journal centre. Film pressure p = 6 eta x (B - x) "
      "(W . u) / h^3 with h = c - e . u and W = de/dt - (omega/2) J e, kept where positive; "
      "force on the journal, reaction on the bearing. Relative spin omega = (w_journal - "
      "w_bearing) . axis + journal_speed. Eccentricity ratio above eps_max: asperity contact "
      "force k_c (e - eps_max c)^n if contact_stiffness > 0, else a run error; e >= c is "
      "always an error. `film` chooses the film model: the paper's short film above "
      "(default), Butenschoen's closed form for finite width, or Reynolds' equation on a grid "
      "with the Swift-Stieber condition (solved at each evaluation or tabulated). See "
      "docs/elements-journal-bearing.md.";
  t.num_markers = 2;
  using P = JournalBearingParams;
  static const ParamBinding<P> binding =
      ParamBinding<P>()
          .required(&P::radius, "radius", "m", "journal radius R", 1e-300)
          .required(&P::width, "width", "m", "bearing width B", 1e-300)
          .required(&P::clearance, "clearance", "m", "radial clearance c", 1e-300)
          .required(&P::viscosity, "viscosity", "Pa s", "dynamic viscosity eta of the oil", 0.0)
          .flag(&P::closed_form, "method",
                "film-force integral: 'ocvirk' = closed form (Sommerfeld substitution) over the "
                "positive-pressure half circle, 'quadrature' = Gauss-Legendre with n_delta points",
                {"ocvirk", "quadrature"}, "ocvirk")
          .whole(&P::n_delta, "n_delta", "-",
                 "quadrature points in the circumferential direction (integer)", 2, 4096)
          .whole(&P::halves, "halves", "-",
                 "1: one station; 2: two axial stations at +-B/(2 sqrt 5) (paper Fig. 6), a "
                 "tilted journal gets a moment",
                 1, 2)
          .number(&P::eps_max, "eps_max", "-", "largest eccentricity ratio of the film alone", 0.0,
                  0.999999)
          .number(&P::contact_stiffness, "contact_stiffness", "N/m^n",
                  "asperity contact coefficient k_c above eps_max (0: exceeding eps_max is an "
                  "error)",
                  0.0)
          .number(&P::contact_exponent, "contact_exponent", "-", "exponent n of the contact law",
                  1.0, 10.0)
          .number(&P::journal_speed, "journal_speed", "rad/s",
                  "spin added to the relative spin (journal bodies that carry no rotation)")
          .choice(&P::film, "film",
                  "film model: 'short' = the paper's short bearing (Ocvirk, pi-film); 'finite' = "
                  "Butenschoen's closed form for finite width (B/D 0.125 to 1); 'reynolds' = "
                  "Reynolds' equation on a grid_phi x grid_axial grid",
                  {"short", "finite", "reynolds"})
          .choice(&P::cavitation, "cavitation",
                  "film 'reynolds': 'swift-stieber' = p >= 0 with the Reynolds (Swift-Stieber) "
                  "condition at the film's rupture; 'none' = the full Sommerfeld film (negative "
                  "pressures kept); 'mass-conserving' = Elrod-Adams' film fraction, the "
                  "ruptured film carried on and re-formed (needs a feed; evas bearing only: "
                  "not yet in a run)",
                  {"swift-stieber", "none", "mass-conserving"})
          .whole(&P::grid_phi, "grid_phi", "-", "film 'reynolds': cells around the circumference",
                 8, 4096)
          .whole(&P::grid_axial, "grid_axial", "-",
                 "film 'reynolds': cells on the half width (the film is symmetric about the "
                 "mid-plane)",
                 1, 1024)
          .flag(&P::table, "solve",
                "film 'reynolds': 'grid' = Reynolds' equation solved at every evaluation; "
                "'table' = the same film tabulated once over the eccentricity ratio (to 0.99) "
                "and the direction of W, interpolated (bicubic; the grid beyond 0.99)",
                {"grid", "table"}, "table")
          .choice(&P::feed, "feed",
                  "film 'reynolds': how oil reaches the film: 'none'; 'axial-grooves' "
                  "(feed_count grooves through the width, evenly spaced from feed_angle, each "
                  "feed_arc wide, rounded to whole cells); 'oil-holes' (feed_count round holes "
                  "feed_diameter across at the mid-plane, evenly spaced from feed_angle: the "
                  "cells whose centres lie inside); 'circumferential-groove' (feed_width wide at "
                  "the mid-plane: two lands); all at supply_pressure",
                  {"none", "axial-grooves", "oil-holes", "circumferential-groove"})
          .number(&P::feed_angle, "feed_angle", "deg",
                  "feed 'axial-grooves', 'oil-holes': the first one's centre, from the bearing's "
                  "x towards y")
          .whole(&P::feed_count, "feed_count", "-",
                 "feed 'axial-grooves', 'oil-holes': how many, evenly spaced", 1, 64)
          .number(&P::feed_arc, "feed_arc", "deg", "feed 'axial-grooves': arc of each groove",
                  1e-300, 359.0)
          .number(&P::feed_width, "feed_width", "m",
                  "feed 'circumferential-groove': the groove's width (below the bearing's)", 0.0)
          .number(&P::feed_diameter, "feed_diameter", "m",
                  "feed 'oil-holes': each hole's diameter (below the bearing's width)", 0.0)
          .number(&P::supply_pressure, "supply_pressure", "Pa",
                  "feed: the oil's pressure in the grooves", 0.0);
  t.params = binding.specs();
  t.make = [](const std::string& name, const std::vector<int>& markers, const ParamValues& v) {
    return std::make_unique<JournalBearing>(name, markers,
                                            binding.read(v, "journal bearing '" + name + "'"));
  };
  return t;
}

}  // namespace evas
