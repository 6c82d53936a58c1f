# Three-storey shear frame with storey 1 run remotely (genericClient): compare with three-storey-reference.tcl
# (the two files differ only in the storey-1 element and its args; diff them). Storey 1 is the specimen.
# Usage: OpenSees three-storey-generic-client.tcl output_dir record_path scale duration_s port [host=127.0.0.1]
# SI units: m, N, kg, s. Nodes: 1 ground (fixed), 2/3/4 floors 1/2/3; DOF 1 horizontal.
source [file join [file dirname [info script]] read-at2.tcl]
set out      [lindex $argv 0]
set record   [lindex $argv 1]
set scale    [expr {[llength $argv] > 2 ? [lindex $argv 2] : 0.1}]
set duration [expr {[llength $argv] > 3 ? [lindex $argv 3] : 20.0}]
set port [lindex $argv 4]
set host [expr {[llength $argv] > 5 ? [lindex $argv 5] : "127.0.0.1"}]
if {$out eq "" || $record eq "" || $port eq ""} { puts stderr "usage: three-storey-generic-client.tcl output_dir record_path scale duration_s port \[host\]"; exit 2 }
file mkdir $out

set m 5000.0;  set k1 700.8e3;  set k2 600e3;  set k3 400e3;  set g 9.80665
set zeta 0.02
set omega1 4.9217210853   ;# rad/s, mode 1 of the elastic frame (eigen; three-storey-whole.tcl prints it)
set dt [expr {1.0/1024.0}]

model basic -ndm 1 -ndf 1
node 1 0.0;  fix 1 1
node 2 0.0 -mass $m
node 3 0.0 -mass $m
node 4 0.0 -mass $m
uniaxialMaterial Elastic 1 $k1
uniaxialMaterial Elastic 2 $k2
uniaxialMaterial Elastic 3 $k3
# storey 1 (the specimen): remote, two basic DOFs (ground, floor 1); the server must already listen
element genericClient 1 -node 1 2 -dof 1 -dof 1 -server $port $host
element zeroLength 2 2 3 -mat 2 -dir 1
element zeroLength 3 3 4 -mat 3 -dir 1

# mass-proportional damping, 2 % in mode 1: C = a0*M
set a0 [expr {2.0*$zeta*$omega1}]
rayleigh $a0 0.0 0.0 0.0

# (OpenSees exits 0 after an uncaught Tcl error, hence catch + exit 2)
if {[catch {read_at2 $record} gm]} { puts stderr $gm; exit 2 }
timeSeries Path 1 -dt [lindex $gm 0] -values [lindex $gm 1] -factor [expr {$scale*$g}]
pattern UniformExcitation 1 1 -accel 1

recorder Node -file $out/displacement.out -precision 16 -time -node 2 3 4 -dof 1 disp
# storey-1 global force, 2 columns: node 1 (ground), node 2 (floor 1), same for both element kinds
recorder Element -file $out/force.out -precision 16 -time -ele 1 force

constraints Plain
numberer Plain
system FullGeneral
algorithm Linear
# explicit (gamma 0.5 = central difference): the tangent holds only M and C, no remote stiffness
integrator NewmarkExplicit 0.5
analysis Transient
set nsteps [expr {int(round($duration/$dt))}]
set rc [analyze $nsteps $dt]
puts "three-storey: analyze $nsteps steps of $dt s -> $rc"
wipe
exit $rc
