# SDOF of the seed paper with the spring run remotely (genericClient): compare with sdof-reference.tcl
# (the two files differ only in the spring element and its args; diff them).
# Usage: OpenSees sdof-generic-client.tcl output_dir record_path scale duration_s port [host=127.0.0.1]
# SI units: m, N, kg, s.
source [file join [file dirname [info script]] read-at2.tcl]
set out      [lindex $argv 0]
set record   [lindex $argv 1]
set scale    [expr {[llength $argv] > 2 ? [lindex $argv 2] : 0.15}]
set duration [expr {[llength $argv] > 3 ? [lindex $argv 3] : 20.0}]
set port [lindex $argv 4]
set host [expr {[llength $argv] > 5 ? [lindex $argv 5] : "127.0.0.1"}]
if {$out eq "" || $record eq "" || $port eq ""} { puts stderr "usage: sdof-generic-client.tcl output_dir record_path scale duration_s port \[host\]"; exit 2 }
file mkdir $out

set m 7080.0;  set k 700.8e3;  set zeta 0.011;  set g 9.80665
set dt [expr {1.0/1024.0}]

model basic -ndm 1 -ndf 1
node 1 0.0;  fix 1 1                ;# ground
node 2 0.0 -mass $m                 ;# the mass
uniaxialMaterial Elastic 1 $k
# spring: remote, one basic DOF (node 2, dof 1); the server must already listen on host:port
element genericClient 1 -node 2 -dof 1 -server $port $host

# damping on the mass only: C = a0*M, a0 = 2*zeta*omega
set a0 [expr {2.0*$zeta*sqrt($k/$m)}]
rayleigh $a0 0.0 0.0 0.0

# (OpenSees exits 0 after an uncaught Tcl error, hence catch + exit 2)
if {[catch {read_at2 $record} gm]} { puts stderr $gm; exit 2 }
timeSeries Path 1 -dt [lindex $gm 0] -values [lindex $gm 1] -factor [expr {$scale*$g}]
pattern UniformExcitation 1 1 -accel 1

recorder Node -file $out/displacement.out -precision 16 -time -node 2 -dof 1 disp
# global element force: reference gives 2 columns (node 1, node 2), client 1 column (node 2) = last column of
# the reference. (genericClient basicForce is useless here: it shows the last reply, i.e. the damping matrix.)
recorder Element -file $out/force.out -precision 16 -time -ele 1 force

constraints Plain
numberer Plain
system FullGeneral
algorithm Linear
# NewmarkExplicit (gamma 0.5 = central difference): explicit, the tangent holds only M and C,
# so a remote element is never asked for its stiffness during the run.
integrator NewmarkExplicit 0.5
analysis Transient
set nsteps [expr {int(round($duration/$dt))}]
set rc [analyze $nsteps $dt]
puts "sdof: analyze $nsteps steps of $dt s -> $rc"
wipe
exit $rc
