#!/bin/sh
# Reference outputs of Aarsnes and Shor (2018), Well B at 2500 m and 40 rpm, from the authors' published MATLAB code
# run under GNU Octave (tests/data/aarsnes_shor_2018/README.md has the provenance). Not run by CI (it needs the fetched
# repository and Octave); the CSVs it writes are committed.
#
#   scripts/reference/aarsnes_shor_octave.sh <checkout of Aarsnes-and-Shor-Torsional-Model> [out_dir] [cells...]
#
# The authors' files are used unchanged (parameters_WellB.m, torsionalWaveStep.m); the loop below is MAIN.m's
# (setpoint ramp, PI top drive sampled every p.dt = 0.01 s, 60 s from rest) without its figures. For each number of
# cells (default 1000, the published grid) two runs: "published" (p.Jc as parameters_WellB.m computes it, with the
# extra factor pi) and "corrected" (p.Jc / pi, the collar's true polar moment). A number of cells other than 1000
# rebuilds the grid-dependent fields exactly as parameters_WellB.m does for its Pt = 1000, and writes two more runs
# ("..._damping-held"): torsionalWaveStep.m applies its damping as 2 kt dt_sub (dt_sub its CFL sub-step, 1/1200 s at
# 1000 cells), so a finer grid also damps less; those runs scale kt to keep the 1000-cell damping rate, which isolates
# the scheme's own grid error.
set -eu
repo=$(cd "${1:?usage: $0 <Aarsnes-and-Shor checkout> [out_dir] [cells...]}" && pwd)
out=$(mkdir -p "${2:-tests/data/aarsnes_shor_2018}" && cd "${2:-tests/data/aarsnes_shor_2018}" && pwd)
shift; [ $# -gt 0 ] && shift
cells=${*:-1000}
for f in MAIN.m parameters_WellB.m torsionalWaveStep.m; do
    [ -f "$repo/$f" ] || { echo "$repo/$f missing" >&2; exit 1; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat > "$work/run_wellb.m" <<'OCT'
function run_wellb(cells, variant, csv, hold_damping)
  mu = .3; fRat = 0.65; oThres = 1.5; MD = 2500;         % MAIN.m
  p = parameters_WellB(MD, mu, fRat, oThres);
  if strcmp(variant, 'corrected'), p.Jc = p.Jc / pi; end  % the collar's polar moment without the extra pi
  if cells ~= 1000                                        % parameters_WellB.m's grid, for another Pt
    p.Pp = round(cells * p.Lp / (p.Lp + p.Lc)); p.Pc = cells - p.Pp;
    p.xp = linspace(0, p.Lp, p.Pp).'; p.xc = p.Lp + linspace(0, p.Lc, p.Pc).';
    MD_prof = [0 500 1600 4000]; inc_prof = [0 0 60 60];
    p.PthetaVec = interp1(MD_prof, inc_prof, p.xp) * pi / 180;
    p.CthetaVec = interp1(MD_prof, inc_prof, p.xc) * pi / 180;
    g = 9.81;
    p.P_thresProfile = g * sin(p.PthetaVec) * p.rho * p.Ap * p.Pro * p.f_thres;
    p.C_thresProfile = g * sin(p.CthetaVec) * p.rho * p.Ac * p.Cro * p.f_thres;
    if hold_damping                                       % keep 2 kt dt_sub, the damping rate of the 1000-cell run
      dt_sub = @(Pp, Pc) .01 / ceil(.01 / min(p.Lp / Pp, p.Lc / Pc) * p.c_t / .99);
      p.kt = p.kt * dt_sub(round(1000 * p.Lp / (p.Lp + p.Lc)), 1000 - round(1000 * p.Lp / (p.Lp + p.Lc))) / dt_sub(p.Pp, p.Pc);
    end
  end
  omega_stat = 40 / 60 * 2 * pi;
  p.dt = .01; t = 0:p.dt:60; Nt = numel(t);
  Pt = p.Pp + p.Pc;
  x = zeros(2 * Pt + 1, 1); u.wb = 0;
  omega_sp = 0; II = 0;
  fid = fopen(csv, 'w');
  fprintf(fid, 'time_s,bit_speed_rad_s,top_drive_speed_rad_s,motor_torque_N_m,stuck_fraction\n');
  for k = 1:Nt                                             % MAIN.m's loop
    omega_sp = omega_sp + (omega_stat - omega_sp) / (1 / p.dt);
    Otd = x(2 * Pt + 1);
    u.tau_Motor = (omega_sp - Otd) * 38e3 + II * 100e3;
    II = II + p.dt * (omega_sp - Otd);
    omega = x(Pt + 1:2 * Pt);
    fprintf(fid, '%.2f,%.9g,%.9g,%.9g,%.6f\n', t(k), x(2 * Pt), Otd, u.tau_Motor, mean(abs(omega) < p.o_thres));
    x = torsionalWaveStep(p, x, u); x = x(:);
  end
  fclose(fid);
end
OCT
cd "$work"
cp "$repo/parameters_WellB.m" "$repo/torsionalWaveStep.m" .
for n in $cells; do
    for variant in published corrected; do
        octave --no-gui --quiet --eval "run_wellb($n, '$variant', '$out/wellb_2500m_40rpm_${n}cells_${variant}.csv', false)"
        echo "wrote $out/wellb_2500m_40rpm_${n}cells_${variant}.csv"
        if [ "$n" != 1000 ]; then
            octave --no-gui --quiet --eval \
                "run_wellb($n, '$variant', '$out/wellb_2500m_40rpm_${n}cells_${variant}_damping-held.csv', true)"
            echo "wrote $out/wellb_2500m_40rpm_${n}cells_${variant}_damping-held.csv"
        fi
    done
done
