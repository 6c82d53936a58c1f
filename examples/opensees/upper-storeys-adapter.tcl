# Storeys 2 and 3 of the three-storey frame as a numerical substructure driven over TCP (rpsd is
# the client). OpenSees listens on $port at the first step; each step it receives the three floor
# displacements, and on request sends back [daqDisp(3), daqForce(3)]; action 99 ends the run.
# Usage: OpenSees upper-storeys-adapter.tcl port material output_dir
#   material: elastic | steel01 (storey 2 only; storey 3 stays elastic)
# SI units: m, N. No masses here (rpsd carries them); nodes 2/3/4 = floors 1/2/3, DOF 1 horizontal.
set port     [lindex $argv 0]
set material [lindex $argv 1]
set out      [lindex $argv 2]
if {$port eq "" || $material ni {elastic steel01} || $out eq ""} {
    puts stderr "usage: upper-storeys-adapter.tcl port elastic|steel01 output_dir"; exit 2
}
file mkdir $out

set k2 600e3;  set k3 400e3
set Fy2 2000.0    ;# N, storey-2 yield force for steel01 (same as three-storey-whole.tcl)
set b2 0.02       ;# steel01 hardening ratio
set kb 1.0e13     ;# N/m, adapter penalty: the floors reach the received displacements to within force/kb

model basic -ndm 1 -ndf 1
# no node is fixed: the adapter's penalty kb on all three DOFs keeps the matrix non-singular
node 2 0.0
node 3 0.0
node 4 0.0
if {$material eq "steel01"} {
    uniaxialMaterial Steel01 2 $Fy2 $k2 $b2
} else {
    uniaxialMaterial Elastic 2 $k2
}
uniaxialMaterial Elastic 3 $k3
element zeroLength 2 2 3 -mat 2 -dir 1   ;# storey 2: floor 1 - floor 2
element zeroLength 3 3 4 -mat 3 -dir 1   ;# storey 3: floor 2 - floor 3
element adapter 99 -node 2 3 4 -dof 1 -dof 1 -dof 1 \
    -stif $kb 0.0 0.0  0.0 $kb 0.0  0.0 0.0 $kb  $port

# the adapter ends the process with exit() on action 99, so close the files on every write
recorder Node -file $out/displacement.out -closeOnWrite -precision 16 -time -node 2 3 4 -dof 1 disp
recorder Element -file $out/storey-force.out -closeOnWrite -precision 16 -time -ele 2 3 basicForce

# static: each "step" (time += 1) is one set of displacements from the client
constraints Plain
numberer Plain
system FullGeneral
test NormDispIncr 1.0e-12 25
algorithm Newton
integrator LoadControl 1.0
analysis Static
set rc [analyze 100000000]
# only reached on a failure (or after 1e8 steps): a normal end exits inside the adapter
puts "upper-storeys-adapter: analyze returned $rc"
exit 1
