#pragma once
// Seawater absorption and the sound speed it is computed with (docs/physics.md §1).
//
// Francois & Garrison, "Sound absorption based on ocean measurements", JASA 72(3) 896-907 and
// 72(6) 1879-1890 (1982): boric acid + magnesium sulphate relaxations + pure-water viscosity.
// Ainslie & McColm, "A simplified formula for viscous and chemical absorption in sea water",
// JASA 103(3) 1671-1672 (1998): a cheaper fit within 10 % of Francois-Garrison.
//
// Both return the absorption coefficient in dB/km; divide by kMetresPerKilometre for the
// dB/m that tvg.h and the renderer take.
namespace sonarloop::acoustics {

inline constexpr double kMetresPerKilometre = 1000.0;

// Sound speed used inside the Francois-Garrison fit, F&G (1982b), as listed in docs/physics.md
// §1: c = 1412 + 3.21 T + 1.19 S + 0.0167 D (m/s). A simple linear fit, good to a few m/s over
// -2..30 °C, 30..40 ppt, D < 5 km; it is the c of the absorption formula, not a general profile.
double sound_speed_fg_m_s(double temperature_c, double salinity_ppt, double depth_m);

// The three relaxation terms of Francois-Garrison, in dB/km (their sum is the absorption).
struct FrancoisGarrisonTerms {
  double boric_acid_db_per_km;
  double magnesium_sulphate_db_per_km;
  double pure_water_db_per_km;
  double total() const {
    return boric_acid_db_per_km + magnesium_sulphate_db_per_km + pure_water_db_per_km;
  }
};

// Francois-Garrison (1982b) absorption split into its three terms (docs/physics.md §1).
// Inputs: frequency (Hz), temperature (°C), salinity (ppt), depth (m), pH.
// The pure-water term uses the warm fit for T >= 20 °C (as Acoustics Toolbox AttenMod.f90 and
// uacpy do) and the cold fit below.
// Validity: 200 Hz - 1 MHz, depth < 5 km; 5 % accuracy in the MgSO4 band (10-500 kHz) needs
// -2..22 °C, 30..35 ppt, depth < 3.5 km. Outside that the fit extrapolates (no clamping).
FrancoisGarrisonTerms francois_garrison_terms(double freq_hz, double temperature_c,
                                              double salinity_ppt, double depth_m, double ph);

// Francois-Garrison (1982b) absorption, dB/km: the sum of francois_garrison_terms().
double francois_garrison_db_per_km(double freq_hz, double temperature_c, double salinity_ppt,
                                   double depth_m, double ph);

// Ainslie & McColm (1998) absorption, dB/km (docs/physics.md §1d). Depth is taken in metres and
// converted to the paper's km inside. Claimed within 10 % of Francois-Garrison for 0.1-1000 kHz,
// -6 < T < 35 °C, 7.7 < pH < 8.3, 5 < S < 50 ppt, 0 < depth < 7 km.
double ainslie_mccolm_db_per_km(double freq_hz, double temperature_c, double salinity_ppt,
                                double depth_m, double ph);

}  // namespace sonarloop::acoustics
