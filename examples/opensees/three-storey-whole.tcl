# Three-storey shear frame, all in OpenSees, central difference: the independent reference for a
# split run (rpsd steps the masses and storey 1; upper-storeys-adapter.tcl carries storeys 2-3).
# Usage: OpenSees three-storey-whole.tcl material output_dir record_path [scale=0.1] [duration_s=20]
#   material: elastic | steel01 (storey 2 only; storeys 1 and 3 stay elastic)
# SI units: m, N, kg, s. Nodes: 1 ground (fixed), 2/3/4 floors 1/2/3; element i = storey i.
source [file join [file dirname [info script]] read-at2.tcl]
set material [lindex $argv 0]
set out      [lindex $argv 1]
set record   [lindex $argv 2]
set scale    [expr {[llength $argv] > 3 ? [lindex $argv 3] : 0.1}]
set duration [expr {[llength $argv] > 4 ? [lindex $argv 4] : 20.0}]
if {$material ni {elastic steel01} || $out eq "" || $record eq ""} {
    puts stderr "usage: three-storey-whole.tcl elastic|steel01 output_dir record_path \[scale\] \[duration_s\]"; exit 2
}
file mkdir $out

set m 5000.0;  set k1 700.8e3;  set k2 600e3;  set k3 400e3;  set g 9.80665
set zeta 0.02
set omega1 4.9217210853   ;# rad/s, mode 1 of the elastic frame; checked with eigen below
set Fy2 2000.0            ;# N, storey-2 yield force for steel01 (same as upper-storeys-adapter.tcl);
                          ;# El Centro x0.1 then gives storey-2 ductility ~2.8 (peak drift 9.2 mm / 3.33 mm)
set b2 0.02               ;# steel01 hardening ratio
set dt [expr {1.0/1024.0}]

model basic -ndm 1 -ndf 1
node 1 0.0;  fix 1 1
node 2 0.0 -mass $m
node 3 0.0 -mass $m
node 4 0.0 -mass $m
uniaxialMaterial Elastic 1 $k1
if {$material eq "steel01"} {
    uniaxialMaterial Steel01 2 $Fy2 $k2 $b2
} else {
    uniaxialMaterial Elastic 2 $k2
}
uniaxialMaterial Elastic 3 $k3
element zeroLength 1 1 2 -mat 1 -dir 1
element zeroLength 2 2 3 -mat 2 -dir 1
element zeroLength 3 3 4 -mat 3 -dir 1

set lambda1 [lindex [eigen -fullGenLapack 1] 0]
puts [format "three-storey-whole: omega1 from eigen %.10f rad/s, used %.10f" [expr {sqrt($lambda1)}] $omega1]

# mass-proportional damping, 2 % in mode 1: C = a0*M
set a0 [expr {2.0*$zeta*$omega1}]
rayleigh $a0 0.0 0.0 0.0

# (OpenSees exits 0 after an uncaught Tcl error, hence catch + exit 2)
if {[catch {read_at2 $record} gm]} { puts stderr $gm; exit 2 }
timeSeries Path 1 -dt [lindex $gm 0] -values [lindex $gm 1] -factor [expr {$scale*$g}]
pattern UniformExcitation 1 1 -accel 1

recorder Node -file $out/displacement.out -precision 16 -time -node 2 3 4 -dof 1 disp
# storey forces k*(upper - lower) for storeys 1, 2, 3 (one column each); storey drifts likewise
recorder Element -file $out/storey-force.out -precision 16 -time -ele 1 2 3 basicForce
recorder Element -file $out/storey-drift.out -precision 16 -time -ele 1 2 3 deformation

constraints Plain
numberer Plain
system FullGeneral
algorithm Linear
integrator CentralDifference
analysis Transient
set nsteps [expr {int(round($duration/$dt))}]
set rc [analyze $nsteps $dt]
puts "three-storey-whole ($material): analyze $nsteps steps of $dt s -> $rc"
wipe
exit $rc
