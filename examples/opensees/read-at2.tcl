# read_at2 path -> {dt values}: a PEER strong-motion record (AT2), values in g.
# Header: 4 lines; the 4th holds NPTS and DT, either "NPTS=  4000, DT= .0100 SEC"
# (NGA-West2) or "4000    0.0100    NPTS, DT" (older NGA). Data follow, several per line.
proc read_at2 {path} {
    set fh [open $path r]
    set text [read $fh]
    close $fh
    set lines [split $text "\n"]
    if {[llength $lines] < 5} {
        error "read_at2: $path: fewer than 5 lines, not a PEER AT2 record"
    }
    set header [lindex $lines 3]
    set num {[-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?}
    if {[regexp -nocase "NPTS\\s*=\\s*(\[0-9\]+)\\s*,?\\s*DT\\s*=\\s*($num)" $header -> npts dt]} {
    } elseif {[regexp "^\\s*(\[0-9\]+)\\s+($num)\\s+NPTS" $header -> npts dt]} {
    } else {
        error "read_at2: $path: line 4 should give NPTS and DT (\"NPTS= n, DT= dt SEC\" or \"n dt NPTS, DT\"), got: \"[string trim $header]\""
    }
    set dt [expr {double($dt)}]
    if {$npts <= 0 || $dt <= 0.0} {
        error "read_at2: $path: NPTS ($npts) and DT ($dt) must be positive"
    }
    set values {}
    foreach line [lrange $lines 4 end] {
        foreach v $line {
            if {![string is double -strict $v]} {
                error "read_at2: $path: not a number in the data: \"$v\""
            }
            lappend values [expr {double($v)}]
        }
    }
    if {[llength $values] < $npts} {
        error "read_at2: $path: header says NPTS=$npts but the file holds [llength $values] values"
    }
    return [list $dt [lrange $values 0 [expr {$npts - 1}]]]
}
