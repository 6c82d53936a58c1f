#!/usr/bin/env bash
# Makes the DDS Security material of an rpsd lab with OpenSSL (docs/dds-security.md):
#   OUT/ca-private/            the two CA keys: keep this folder offline, never on a test host
#   OUT/identity_ca.pem        identity CA certificate (every host)
#   OUT/permissions_ca.pem     permissions CA certificate (every host)
#   OUT/governance.p7s         transport/config/security/governance.xml signed by the permissions CA
#   OUT/identity_ca.crl.pem    the identity CA's revocation list (every host; empty at first)
#   OUT/identities/NAME/       identity.pem (certificate), identity_key.pem (private key, that
#                              host only), permissions.xml and its signed permissions.p7s
#   OUT/revoked/NAME-SERIAL/   what a revoked identity had (--revoke)
# Identities: coordinator, node-site-1..N (one per site), monitor (read-only), operator (may
# send operator commands: stop, abort, hold, resume), and any given with --identity. Running it again reuses the CAs and the identities' keys and renews the
# certificates and the signed documents, so an identity can be added or re-granted later.
# A host may keep its key to itself: put its certificate request (made on that host, see
# docs/dds-security.md) at OUT/identities/NAME/identity.csr and no key; the script signs it.
set -euo pipefail

usage() {
  cat <<EOF
usage: $0 [options] OUT_DIR
  --sites N                 node identities node-site-1..N (default 2)
  --identity NAME:ROLE[:SITE]
                            one more identity; ROLE is coordinator, node (needs SITE),
                            monitor or operator (repeatable)
  --lab NAME                organisation in the certificates' subjects (default "rpsd lab")
  --test-ids PATTERN        test ids the grants cover, an fnmatch pattern (default "*")
  --domains MIN-MAX         DDS domains the grants cover (default 0-230, all of them)
  --days N                  validity of certificates, grants and the revocation list
                            (default 365)
  --ca-days N               validity of the two CA certificates, made on the first run
                            only (default 3650)
  --revoke NAME             revoke NAME's certificate (a lost or compromised host) and
                            move its folder to OUT/revoked; an identity still in the list
                            above gets a new key and certificate (repeatable)
EOF
  exit 2
}

sites=2
lab="rpsd lab"
test_ids="*"
domain_min=0
domain_max=230
days=365
ca_days=3650
extra=()
revoke=()
out=""
while [ $# -gt 0 ]; do
  case "$1" in
    --sites) sites=${2:?}; shift 2 ;;
    --identity) extra+=("${2:?}"); shift 2 ;;
    --lab) lab=${2:?}; shift 2 ;;
    --test-ids) test_ids=${2:?}; shift 2 ;;
    --domains) domain_min=${2%-*}; domain_max=${2#*-}; shift 2 ;;
    --days) days=${2:?}; shift 2 ;;
    --ca-days) ca_days=${2:?}; shift 2 ;;
    --revoke) revoke+=("${2:?}"); shift 2 ;;
    -h|--help) usage ;;
    -*) echo "$0: unknown option $1" >&2; usage ;;
    *) [ -z "$out" ] || usage; out=$1; shift ;;
  esac
done
[ -n "$out" ] || usage
[[ "$sites" =~ ^[0-9]+$ && "$days" =~ ^[1-9][0-9]*$ && "$ca_days" =~ ^[1-9][0-9]*$ && "$domain_min" =~ ^[0-9]+$ \
   && "$domain_max" =~ ^[0-9]+$ ]] || { echo "$0: --sites, --days, --ca-days and --domains take whole numbers" >&2; exit 2; }
(( domain_min <= domain_max && domain_max <= 230 )) || { echo "$0: --domains: MIN <= MAX <= 230" >&2; exit 2; }
[[ "$lab" =~ ^[A-Za-z0-9._-]([A-Za-z0-9\ ._-]*[A-Za-z0-9._-])?$ ]] \
  || { echo "$0: --lab: letters, digits, space . _ - only, no space at either end" >&2; exit 2; }
[[ "$test_ids" =~ ^[0-9*?]+$ ]] || { echo "$0: --test-ids: digits, * and ? only" >&2; exit 2; }
command -v openssl >/dev/null || { echo "$0: openssl not found" >&2; exit 1; }

templates="$(cd "$(dirname "$0")/.." && pwd)/transport/config/security"
mkdir -p "$out/ca-private" "$out/identities"
chmod 700 "$out/ca-private"
out=$(cd "$out" && pwd)

# EC P-256 keys: accepted by Cyclone's authentication plugin (as is RSA-2048), and cheaper
# to sign and verify with during the handshake.
new_key() { (umask 077; openssl genpkey -algorithm EC -pkeyopt ec_paramgen_curve:P-256 -out "$1" 2>/dev/null); }

# A self-signed CA, made once. The permissions CA signs the documents itself (S/MIME), so
# its key usage includes digitalSignature: OpenSSL refuses the signer otherwise.
make_ca() {
  local key=$1 cert=$2 cn=$3 usage=$4
  [ -f "$key" ] || new_key "$key"
  if [ ! -f "$cert" ]; then
    openssl req -x509 -new -key "$key" -sha256 -days "$ca_days" -out "$cert" -subj "/O=$lab/CN=$cn" \
      -addext "basicConstraints=critical,CA:TRUE" -addext "keyUsage=critical,$usage" 2>/dev/null
  fi
}
make_ca "$out/ca-private/identity_ca_key.pem" "$out/identity_ca.pem" "$lab identity CA" keyCertSign,cRLSign
make_ca "$out/ca-private/permissions_ca_key.pem" "$out/permissions_ca.pem" "$lab permissions CA" digitalSignature,keyCertSign,cRLSign

# Revocation: an `openssl ca` database of revoked identity certificates, published as a CRL
# that every participant loads (Cyclone's Authentication/CRL) and checks peers against.
ca_conf="$out/ca-private/identity_ca.cnf"
cat > "$ca_conf" <<EOF
[ ca ]
default_ca = identity_ca
[ identity_ca ]
database = $out/ca-private/identity_ca_index.txt
crlnumber = $out/ca-private/identity_ca_crlnumber
certificate = $out/identity_ca.pem
private_key = $out/ca-private/identity_ca_key.pem
default_md = sha256
default_crl_days = $days
unique_subject = no
EOF
[ -f "$out/ca-private/identity_ca_index.txt" ] || : > "$out/ca-private/identity_ca_index.txt"
[ -f "$out/ca-private/identity_ca_crlnumber" ] || echo 01 > "$out/ca-private/identity_ca_crlnumber"
for name in "${revoke[@]}"; do
  cert="$out/identities/$name/identity.pem"
  [ -f "$cert" ] || { echo "$0: --revoke $name: no $cert" >&2; exit 2; }
  serial=$(openssl x509 -in "$cert" -noout -serial | sed 's/^serial=//')
  openssl ca -config "$ca_conf" -revoke "$cert" -crl_reason keyCompromise 2>/dev/null
  mkdir -p "$out/revoked"
  mv "$out/identities/$name" "$out/revoked/$name-$serial"
  echo "$name: certificate $serial revoked"
done
openssl ca -config "$ca_conf" -gencrl -out "$out/identity_ca.crl.pem" 2>/dev/null

# S/MIME (multipart/signed, signer certificate included), the form Cyclone's access control reads.
sign() { openssl smime -sign -text -in "$1" -out "$2" -signer "$out/permissions_ca.pem" -inkey "$out/ca-private/permissions_ca_key.pem"; }

sign "$templates/governance.xml" "$out/governance.p7s"

not_before=$(date -u -d "-1 day" +%Y-%m-%dT00:00:00)
not_after=$(date -u -d "+$days days" +%Y-%m-%dT%H:%M:%S)

# make_identity NAME ROLE [SITE]: certificate (and key unless a request waits), signed grant.
make_identity() {
  local name=$1 role=$2 site=${3:-}
  [[ "$name" =~ ^[A-Za-z0-9._-]+$ ]] || { echo "$0: identity name \"$name\": letters, digits . _ - only" >&2; exit 2; }
  case "$role" in
    coordinator|monitor|operator) ;;
    node) [[ "$site" =~ ^[0-9]+$ ]] || { echo "$0: identity $name: a node needs its site id" >&2; exit 2; } ;;
    *) echo "$0: identity $name: unknown role \"$role\" (coordinator, node, monitor, operator)" >&2; exit 2 ;;
  esac
  local dir="$out/identities/$name"
  mkdir -p "$dir"
  if [ ! -f "$dir/identity.csr" ] || [ -f "$dir/identity_key.pem" ]; then
    [ -f "$dir/identity_key.pem" ] || new_key "$dir/identity_key.pem"
    openssl req -new -key "$dir/identity_key.pem" -out "$dir/identity.csr" -subj "/O=$lab/OU=$role/CN=$name"
  fi
  # A request made elsewhere must ask for exactly this identity's subject: a grant binds to the
  # subject, so a request for another identity's subject would borrow that identity's grant.
  local asked
  asked=$(openssl req -in "$dir/identity.csr" -noout -subject -nameopt RFC2253 | sed 's/^subject=//')
  if [ "$asked" != "CN=$name,OU=$role,O=$lab" ]; then
    echo "$0: $dir/identity.csr asks for \"$asked\", not \"CN=$name,OU=$role,O=$lab\"" >&2
    exit 1
  fi
  local ext
  ext=$(mktemp)
  printf 'basicConstraints=critical,CA:FALSE\nkeyUsage=critical,digitalSignature\n' > "$ext"
  openssl x509 -req -in "$dir/identity.csr" -CA "$out/identity_ca.pem" -CAkey "$out/ca-private/identity_ca_key.pem" \
    -CAcreateserial -CAserial "$out/ca-private/identity_ca.srl" -sha256 -days "$days" -extfile "$ext" \
    -out "$dir/identity.pem" 2>/dev/null
  rm -f "$ext"
  # The grant names the certificate's subject exactly as Cyclone compares it.
  local subject
  subject=$(openssl x509 -in "$dir/identity.pem" -noout -subject -nameopt RFC2253 | sed 's/^subject=//')
  sed -e "s|@NAME@|$name|" -e "s|@SUBJECT@|$subject|" -e "s|@NOT_BEFORE@|$not_before|" -e "s|@NOT_AFTER@|$not_after|" \
      -e "s|@DOMAIN_MIN@|$domain_min|" -e "s|@DOMAIN_MAX@|$domain_max|" -e "s|@TEST@|$test_ids|g" -e "s|@SITE@|$site|g" \
      "$templates/permissions-$role.xml.in" > "$dir/permissions.xml"
  sign "$dir/permissions.xml" "$dir/permissions.p7s"
  echo "$name ($role${site:+ of site $site}): $subject"
}

make_identity coordinator coordinator
for ((s = 1; s <= sites; ++s)); do make_identity "node-site-$s" node "$s"; done
make_identity monitor monitor
make_identity operator operator
for spec in "${extra[@]}"; do
  IFS=: read -r name role site <<< "$spec"
  make_identity "$name" "$role" "$site"
done
echo "Lab security material in $out (CA keys in $out/ca-private: keep them offline)."
